// nimbus::sdk::Guide (nimbus.hpp) fills the C guiding table like Integrator and LightSampler fill theirs:
// this file compiling is the check that the wrapper matches nimbus_guiding_v1_t member for member; the
// tests drive the table as a host or integrator would, without loading a library.
#include <gtest/gtest.h>
#include <nimbus/nimbus.hpp>

#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace {

std::vector<std::string> g_log;

const nimbus_host_t kHost = {
    sizeof(nimbus_host_t), NIMBUS_ABI_VERSION_INIT, nullptr,
    [](const nimbus_host_t *, const char *, uint32_t) -> const void * { return nullptr; },
    [](const nimbus_host_t *, nimbus_log_level_t, const char *id, const char *msg) {
      g_log.push_back(std::string(id ? id : "") + ": " + msg);
    }};

class CountingGuide final : public nimbus::sdk::Guide {
 public:
  NIMBUS_DESCRIPTOR("org.nimbus.test.guide", "wrapper guide", "tests", NIMBUS_KIND_GUIDING, 1, 0, 0, nullptr,
                    nullptr)
  uint64_t budget() override {
    if (throw_) throw std::runtime_error("budget failed");
    return 8;
  }
  void propose(const nimbus_thread_ctx_t &ctx, uint64_t path, float *u, uint32_t dims) override {
    if (throw_) throw std::runtime_error("propose failed");
    for (uint32_t i = 0; i < dims; ++i) u[i] = float(path + ctx.worker_index) / 16.0f;
  }
  void report(const nimbus_thread_ctx_t &, uint64_t, bool visible) override { visible_ += visible; }
  void end_iteration(uint64_t, const nimbus_guide_stats_t &s) override { traced_ = s.paths_traced; }

  bool throw_ = false;
  int visible_ = 0;
  uint64_t traced_ = 0;
};

static_assert(std::is_abstract_v<nimbus::sdk::Guide>, "budget and propose must be overridden");
static_assert(!std::is_copy_constructible_v<nimbus::sdk::Guide>, "plugin instances are not copyable");

using Library = nimbus::sdk::detail::Library<CountingGuide>;

class GuideWrapper : public ::testing::Test {
 protected:
  void SetUp() override {
    g_log.clear();
    ASSERT_EQ(Library::entry().create("org.nimbus.test.guide", &kHost, &plugin_), NIMBUS_OK);
    guide_ = static_cast<CountingGuide *>(nimbus::sdk::Plugin::from(plugin_));
    table_ =
        static_cast<const nimbus_guiding_v1_t *>(plugin_->get_interface(plugin_, NIMBUS_IFACE_GUIDING, 1));
  }
  void TearDown() override { plugin_->destroy(plugin_); }

  const nimbus_plugin_t *plugin_ = nullptr;
  CountingGuide *guide_ = nullptr;
  const nimbus_guiding_v1_t *table_ = nullptr;
  const nimbus_thread_ctx_t ctx_{sizeof(nimbus_thread_ctx_t), 1, 2, 0, nullptr, 0};
};

TEST_F(GuideWrapper, ServesOnlyTheGuidingInterface) {
  ASSERT_NE(table_, nullptr);
  EXPECT_EQ(table_->struct_size, sizeof(nimbus_guiding_v1_t));
  EXPECT_EQ(plugin_->get_interface(plugin_, NIMBUS_IFACE_GUIDING, 2), nullptr) << "unknown revision";
  EXPECT_EQ(plugin_->get_interface(plugin_, NIMBUS_IFACE_INTEGRATOR, 1), nullptr);
  EXPECT_EQ(Library::entry().descriptor(0)->kind, NIMBUS_KIND_GUIDING);
}

TEST_F(GuideWrapper, HooksReachTheVirtuals) {
  nimbus_scene_info_t info{};
  info.header = {sizeof info, NIMBUS_S_TYPE_SCENE_INFO, nullptr};
  EXPECT_EQ(table_->prepare(plugin_, &info), NIMBUS_OK) << "default prepare succeeds";
  EXPECT_EQ(table_->begin_iteration(plugin_, 1), NIMBUS_OK);
  EXPECT_EQ(table_->budget(plugin_), 8u);
  float u[3] = {-1, -1, -1};
  table_->propose(plugin_, &ctx_, 3, u, 3);
  for (float v : u) EXPECT_EQ(v, 0.25f);
  table_->report(plugin_, &ctx_, 3, 1);
  table_->report(plugin_, &ctx_, 4, 0);
  EXPECT_EQ(guide_->visible_, 1);
  const nimbus_guide_stats_t stats{sizeof stats, 0, 5, 1};
  table_->end_iteration(plugin_, 1, &stats);
  EXPECT_EQ(guide_->traced_, 5u);
  EXPECT_TRUE(g_log.empty());
}

TEST_F(GuideWrapper, ExceptionsAreLoggedAndDegradeToNoGuidance) {
  guide_->throw_ = true;
  EXPECT_EQ(table_->budget(plugin_), 0u);
  float u[2] = {-1, -1};
  table_->propose(plugin_, &ctx_, 0, u, 2);
  EXPECT_EQ(u[0], 0.0f);
  EXPECT_EQ(u[1], 0.0f);
  ASSERT_EQ(g_log.size(), 2u);
  EXPECT_EQ(g_log[0], "org.nimbus.test.guide: budget: budget failed");
  EXPECT_EQ(g_log[1], "org.nimbus.test.guide: propose: propose failed");
}

}  // namespace
