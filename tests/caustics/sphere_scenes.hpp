// Caustic scenes and measurements shared by the solver's render tests: a glass sphere on a floor, region
// means and relMSE, and the convergence check against nimbus.lt (which renders the caustics of point
// lights and small suns seen directly).
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "support/render_support.hpp"

namespace nimbus::testing {

// A glass sphere on a floor lit from the side, seen from above so that the caustic is not hidden.
// sphere_extra: more keys of the sphere (e.g. its motion).
inline std::string sphere_scene(
    const std::string &light, int width = 80, int height = 45,
    const char *camera = "{ position: [1.6, -1.8, 2.4], look_at: [0.5, 0.05, 0.05], up: [0, 0, 1], fov: 36 }",
    const std::string &sphere_extra = "") {
  return R"(
render: { resolution: [)" +
         std::to_string(width) + ", " + std::to_string(height) + R"(], seed: 3, max_depth: 10 }
camera: )" +
         std::string(camera) + R"(
materials:
  floor: { type: diffuse, albedo: [0.7, 0.7, 0.7] }
  glass: { type: dielectric, ior: 1.5 }
  lamp:  { type: diffuse, albedo: [0, 0, 0] }
objects:
  - { shape: rectangle, size: [6, 6], material: floor }
  - { shape: sphere, center: [0, 0, 0.5], radius: 0.5, material: glass)" +
         sphere_extra + R"( }
)" + light;
}

inline RenderRequest request(const std::string &integrator, uint64_t iterations, uint64_t seed,
                             std::vector<std::string> elements = {}) {
  RenderRequest r;
  r.integrator = integrator;
  r.iterations = iterations;
  r.seed = seed;
  r.elements = std::move(elements);
  return r;
}

inline double stat(const ImageLayers &img, const std::string &name) {
  const auto it = img.numbers.find("nimbus:stat:" + name);
  return it == img.numbers.end() ? -1.0 : it->second;
}

// Mean luminance and relMSE over a pixel rectangle [x0, x1) x [y0, y1).
struct Region {
  uint32_t x0, y0, x1, y1;
};

inline double region_mean(const ImageLayers &img, const Region &r) {
  const std::vector<float> &d = img.layers.at("beauty").data;
  double s = 0;
  for (uint32_t y = r.y0; y < r.y1; ++y)
    for (uint32_t x = r.x0; x < r.x1; ++x) s += luminance(Rgb::load(&d[3 * (size_t(y) * img.width + x)]));
  return s / double((r.x1 - r.x0) * (r.y1 - r.y0));
}

inline double region_rel_mse(const ImageLayers &test, const ImageLayers &ref, const Region &r) {
  const std::vector<float> &t = test.layers.at("beauty").data, &f = ref.layers.at("beauty").data;
  double s = 0;
  for (uint32_t y = r.y0; y < r.y1; ++y)
    for (uint32_t x = r.x0; x < r.x1; ++x) {
      const size_t i = 3 * (size_t(y) * test.width + x);
      const double a = luminance(Rgb::load(&t[i])), b = luminance(Rgb::load(&f[i]));
      s += (a - b) * (a - b) / (b * b + 0.01);
    }
  return s / double((r.x1 - r.x0) * (r.y1 - r.y0));
}

// The solver converges to light tracing (which renders caustics of point lights and small suns seen
// directly): relMSE over the caustic falls from the probe-only map to a few hundred iterations, and the
// region mean matches. Seen from above so that the region holds floor only (light tracing cannot see
// through the sphere).
// options: the solver's (e.g. guided photon emission); min_fall: how much the error between two renders
// must fall from 8 to 256 iterations; scale: the image's size in units of 80 x 45 pixels.
// The scene: sphere_scene seen from above (from_above), lit by `lights`.
inline std::string from_above(const std::string &lights, uint32_t scale = 1,
                              const std::string &camera_extra = "", const std::string &sphere_extra = "") {
  return sphere_scene(
      lights, 80 * int(scale), 45 * int(scale),
      ("{ position: [0.6, -1.2, 3.6], look_at: [0.6, 0, 0], up: [0, 0, 1], fov: 40" + camera_extra + " }")
          .c_str(),
      sphere_extra);
}
inline void converges_to_light_tracer_in(const std::string &scene,
                                         const std::vector<std::pair<std::string, std::string>> &options = {},
                                         double min_fall = 2.0, uint32_t scale = 1) {
  SceneRenderer r;
  const Region caustic{40 * scale, 14 * scale, 60 * scale, 32 * scale},
      core{44 * scale, 18 * scale, 52 * scale, 24 * scale};
  const auto lt = r.render(scene, request("nimbus.lt", 2048, 34));
  const auto solver = [&](uint64_t iterations, uint64_t seed) {
    RenderRequest q = request("nimbus.caustics", iterations, seed);
    q.options = options;
    return r.render(scene, q);
  };
  const auto s1 = solver(8, 31), s1b = solver(8, 32), s2 = solver(256, 33), s3 = solver(256, 35);
  // The error of the solver alone, from two independent renders at each count (the light tracer's own
  // noise would set a floor under a comparison with it). In this small image it is photon-limited: the
  // 8 iterations share the probe's map, 256 iterations have ~7.5x its photon paths over ~10 passes, and
  // the merge variance ~ 1 / (photon paths r^2) with r^2 ~ j^-1/4 falls ~4x.
  const double e1 = region_rel_mse(s1, s1b, caustic), e2 = region_rel_mse(s2, s3, caustic);
  std::printf(
      "caustic region: relMSE between two renders %.4g at 8 iterations (%.0f photon paths), %.4g at "
      "256 (%.0f); against lt %.4g at 256\n",
      e1, stat(s1, "caustics_photon_paths"), e2, stat(s2, "caustics_photon_paths"),
      region_rel_mse(s2, lt, caustic));
  // Two independent renders: the photon noise of a region mean is heavy-tailed.
  const double mean = (region_mean(s2, caustic) + region_mean(s3, caustic)) / 2;
  const double mean_core = (region_mean(s2, core) + region_mean(s3, core)) / 2;
  std::printf("region mean %.4f vs lt %.4f; core %.4f vs %.4f\n", mean, region_mean(lt, caustic), mean_core,
              region_mean(lt, core));
  EXPECT_GT(e1 / e2, min_fall);
  for (const auto &[key, value] : options) {
    if (value == "guided") {
      EXPECT_GT(stat(s2, "caustics_guided_passes"), 0.0);
    }
    if (value == "adaptive-map") {
      EXPECT_GT(stat(s2, "caustics_emission_map_slots"), 0.0);
    }
  }
  EXPECT_NEAR(mean / region_mean(lt, caustic), 1.0, 0.03);
  EXPECT_NEAR(mean_core / region_mean(lt, core), 1.0, 0.04);
}

inline void converges_to_light_tracer(const std::string &lights,
                                      const std::vector<std::pair<std::string, std::string>> &options = {},
                                      double min_fall = 2.0, uint32_t scale = 1) {
  converges_to_light_tracer_in(from_above(lights, scale), options, min_fall, scale);
}

// Under an area light path tracing converges on the caustic too: the relMSE between a solver and a PT
// render falls with iterations as their noise does (8x the iterations: > 3x lower; the noise alone
// gives 8x), and the image means agree within 2 %.
inline void agrees_with_path_tracer(const std::string &scene) {
  SceneRenderer r;
  const uint64_t n = 16;
  const auto s1 = r.render(scene, request("nimbus.caustics", n, 21));
  const auto p1 = r.render(scene, request("nimbus.pt", n, 22));
  const auto s8 = r.render(scene, request("nimbus.caustics", 8 * n, 23));
  const auto p8 = r.render(scene, request("nimbus.pt", 8 * n, 24));
  const double e1 = rel_mse(s1.layers.at("beauty").data, p1.layers.at("beauty").data);
  const double e8 = rel_mse(s8.layers.at("beauty").data, p8.layers.at("beauty").data);
  std::printf("relMSE(solver, pt): %.4g at %llu iterations, %.4g at %llu (ratio %.2f)\n", e1,
              (unsigned long long)n, e8, (unsigned long long)(8 * n), e1 / e8);
  EXPECT_GT(stat(s8, "caustics_photon_paths"), 0.0);
  EXPECT_GT(e1 / e8, 3.0);
  const Rgb ms = mean_rgb(s8.layers.at("beauty").data), mp = mean_rgb(p8.layers.at("beauty").data);
  EXPECT_NEAR(luminance(ms) / luminance(mp), 1.0, 0.02);
}

}  // namespace nimbus::testing
