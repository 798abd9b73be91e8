// Rendering a scene in-process for statistical tests: the real registry, plugins from the build tree,
// output into a scratch directory, read back as layers. Header-only; include from any test binary.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <nimbus/cpp/math.hpp>
#include "abi/host_services.hpp"
#include "film/image_read.hpp"
#include "loader/plugin_registry.hpp"
#include "render/render_session.hpp"
#include "scene/scene_parser.hpp"

namespace nimbus::testing {

struct RenderRequest {
  std::string integrator;  // empty: the scene's
  uint64_t iterations = 16;
  uint64_t seed = 1;
  uint32_t threads = 2;
  std::vector<std::string> elements;
  std::vector<std::pair<std::string, std::string>> options;  // integrator options, e.g. caustics=on
  std::string light_sampler;                                 // empty: the host's choice
  std::string guide;                                         // empty: the integrator's default
  double target_error = 0;                                   // > 0: stop at this estimated relMSE
};

class SceneRenderer {
 public:
  // extra_plugin_dirs: test fixtures' directories, searched after the build's plugins.
  explicit SceneRenderer(const std::vector<std::string> &extra_plugin_dirs = {})
      : registry_([](int, const std::string &) {}) {
    std::vector<std::string> dirs = {std::string(NIMBUS_BINARY_DIR) + "/lib/nimbus/plugins"};
    dirs.insert(dirs.end(), extra_plugin_dirs.begin(), extra_plugin_dirs.end());
    registry_.discover(dirs, discovery_.host());
    dir_ = std::filesystem::temp_directory_path() /
           ("nimbus-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter_++));
    std::filesystem::create_directories(dir_);
  }
  ~SceneRenderer() {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }

  // Renders `yaml` and returns its layers (fails the test on error).
  ImageLayers render(const std::string &yaml, const RenderRequest &r) {
    auto desc = parse_scene_string(yaml, "test.yaml");
    EXPECT_TRUE(desc.ok()) << (desc.ok() ? "" : desc.error().message);
    if (!desc.ok()) return {};
    SceneDesc d = std::move(desc.value());
    if (!r.integrator.empty()) d.render.integrator = r.integrator;
    for (const auto &[k, v] : r.options) d.render.options.push_back({k, v, "request option " + k, ""});
    RenderOptions opt;
    if (r.iterations) opt.iterations = r.iterations;  // 0: the scene decides
    opt.seed = r.seed;
    opt.threads = r.threads;
    opt.elements = r.elements;
    opt.light_sampler = r.light_sampler;
    opt.guide = r.guide;
    if (r.target_error > 0) opt.target_error = r.target_error, opt.iterations.reset();
    opt.output_exr = (dir_ / ("out" + std::to_string(renders_++) + ".exr")).string();
    std::atomic<bool> cancel{false};
    auto result = nimbus::render(d, opt, registry_, cancel, {}, {});
    EXPECT_TRUE(result.ok()) << (result.ok() ? "" : result.error().message);
    if (!result.ok()) return {};
    auto layers = read_exr_layers(opt.output_exr);
    EXPECT_TRUE(layers.ok()) << (layers.ok() ? "" : layers.error().message);
    return layers.ok() ? std::move(layers.value()) : ImageLayers{};
  }

 private:
  static inline int counter_ = 0;
  HostServices discovery_{nullptr};
  PluginRegistry registry_;
  std::filesystem::path dir_;
  int renders_ = 0;
};

// relMSE of `test` against `ref` (interleaved RGB), on luminance: mean (t - r)^2 / (r^2 + 0.01).
// cap: the most one pixel's term may add (a firefly's weight), unbounded unless given.
inline double rel_mse(const std::vector<float> &test, const std::vector<float> &ref,
                      double cap = std::numeric_limits<double>::infinity()) {
  double sum = 0;
  const size_t n = ref.size() / 3;
  for (size_t i = 0; i < n; ++i) {
    const double t = luminance(Rgb::load(&test[3 * i])), r = luminance(Rgb::load(&ref[3 * i]));
    sum += std::min(cap, (t - r) * (t - r) / (r * r + 0.01));
  }
  return n ? sum / double(n) : 0;
}

// Mean of the beauty layer over image pixels [x0, x1) x [y0, y1) (row 0 at the top).
inline Rgb region_mean(const ImageLayers &img, int x0, int x1, int y0, int y1) {
  const std::vector<float> &px = img.layers.at("beauty").data;
  Rgb sum(0.0f);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) sum += Rgb::load(&px[3 * (size_t(y) * img.width + size_t(x))]);
  return sum / float((x1 - x0) * (y1 - y0));
}

inline Rgb mean_rgb(const std::vector<float> &img) {
  double s[3] = {0, 0, 0};
  for (size_t i = 0; i < img.size(); ++i) s[i % 3] += img[i];
  const double n = double(img.size() / 3);
  return {float(s[0] / n), float(s[1] / n), float(s[2] / n)};
}

// The mean of independent estimates (renders of several seeds) and its standard error.
inline std::pair<double, double> mean_and_se(const std::vector<double> &v) {
  double m = 0, s2 = 0;
  for (double x : v) m += x / double(v.size());
  for (double x : v) s2 += (x - m) * (x - m) / double(v.size() - 1);
  return {m, std::sqrt(s2 / double(v.size()))};
}

}  // namespace nimbus::testing
