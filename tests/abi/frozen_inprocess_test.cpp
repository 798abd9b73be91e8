// The frozen 1.0 fixtures driven in-process: the loader's view of them, and the guide, which the host
// does not bind to a render yet, driven through its table directly.
#include <gtest/gtest.h>
#include <nimbus/guiding.h>

#include "abi/host_services.hpp"
#include "abi_test_support.hpp"
#include "loader/plugin_registry.hpp"

namespace nimbus::abi_test {
namespace frozen_inprocess_test {

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

}  // namespace frozen_inprocess_test
}  // namespace nimbus::abi_test
