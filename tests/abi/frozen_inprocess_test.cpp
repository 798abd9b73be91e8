// The frozen 1.0 fixtures driven in-process where the CLI cannot reach them: the uniform light sampler
// (the CLI picks the sampler itself) and the guide (the host binds no guide yet).
#include <gtest/gtest.h>
#include <nimbus/guiding.h>

#include <atomic>
#include <cstring>

#include "abi/host_services.hpp"
#include "abi_test_support.hpp"
#include "render/plugin_registry.hpp"
#include "render/render_session.hpp"
#include "scene/scene_parser.hpp"

namespace nimbus::abi_test {
namespace {

class FrozenAbi10InProcess : public ::testing::Test {
 protected:
  void SetUp() override { registry_.discover({fixture_dir()}, discovery_.host()); }

  HostServices discovery_{nullptr};
  std::vector<std::string> log_;
  PluginRegistry registry_{[this](int, const std::string &line) { log_.push_back(line); }};
};

TEST_F(FrozenAbi10InProcess, EveryFixtureLoadsWithAbi10) {
  int loaded = 0;
  for (const PluginRecord &r : registry_.records()) {
    EXPECT_TRUE(r.loaded) << r.path << ": " << r.status;
    EXPECT_EQ(r.abi.major, 1) << r.path;
    EXPECT_EQ(r.abi.minor, 0) << r.path;
    loaded += r.loaded;
  }
  EXPECT_EQ(loaded, 4) << "two libraries of two plugins each";
}

TEST_F(FrozenAbi10InProcess, UniformSamplerRendersTheReference) {
  ScratchDir dir;
  auto desc = parse_scene_file(scene_path());
  ASSERT_TRUE(desc) << desc.error().message;
  RenderOptions options;
  options.output_exr = dir.file("uniform.exr");
  options.elements = {"caustics"};
  options.light_sampler = "org.nimbus.abi.uniform";
  std::atomic<bool> cancel{false};
  auto result = render(desc.value(), options, registry_, cancel, {}, {});
  ASSERT_TRUE(result) << result.error().message;
  auto img = read_exr_layers(options.output_exr);
  ASSERT_TRUE(img) << img.error().message;
  EXPECT_EQ(img.value().strings["nimbus:light_sampler"], "org.nimbus.abi.uniform");
  expect_finite_layer(img.value(), "beauty");
  expect_finite_layer(img.value(), "caustics");
  // One light: uniform and power-proportional picking are the same distribution, so the image the CLI's
  // default sampler produced is the reference here too.
  auto ref = read_exr_layers(reference_path());
  ASSERT_TRUE(ref) << ref.error().message;
  EXPECT_LE(relative_rmse(img.value(), ref.value(), "beauty"), kReferenceTolerance);
}

TEST_F(FrozenAbi10InProcess, GuideAnswersThroughItsTable) {
  auto created = registry_.create("org.nimbus.abi.cpp.guide", NIMBUS_KIND_GUIDING, discovery_.host());
  ASSERT_TRUE(created) << created.error().message;
  const nimbus_plugin_t *guide = created.value();
  EXPECT_EQ(guide->get_interface(guide, NIMBUS_IFACE_GUIDING, 2), nullptr) << "unknown revision";
  EXPECT_EQ(guide->get_interface(guide, NIMBUS_IFACE_INTEGRATOR, 1), nullptr);
  const auto *g =
      static_cast<const nimbus_guiding_v1_t *>(guide->get_interface(guide, NIMBUS_IFACE_GUIDING, 1));
  ASSERT_NE(g, nullptr);
  ASSERT_GE(g->struct_size, sizeof(nimbus_guiding_v1_t));

  nimbus_scene_info_t info{};
  info.header = {sizeof info, NIMBUS_S_TYPE_SCENE_INFO, nullptr};
  info.light_count = 1;
  info.worker_count = 1;
  EXPECT_EQ(g->prepare(guide, &info), NIMBUS_OK);
  EXPECT_EQ(g->begin_iteration(guide, 1), NIMBUS_OK);
  EXPECT_EQ(g->budget(guide), 0u) << "a null guide asks for no photon paths";
  const nimbus_thread_ctx_t ctx{sizeof ctx, 0, 1, 0, nullptr, 0};
  float u[4] = {-1, -1, -1, -1};
  g->propose(guide, &ctx, 0, u, 4);
  for (float v : u) EXPECT_EQ(v, 0.5f);
  g->report(guide, &ctx, 0, 1);
  const nimbus_guide_stats_t stats{sizeof stats, 0, 1, 1};
  g->end_iteration(guide, 1, &stats);
  registry_.destroy(guide);
}

}  // namespace
}  // namespace nimbus::abi_test
