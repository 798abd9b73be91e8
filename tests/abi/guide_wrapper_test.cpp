// nimbus::sdk::Guide (nimbus.hpp) and nimbus::sdk::PhotonGuide (nimbus/cpp/photon_guide.hpp) fill the C
// guiding tables of rev 1 and rev 2 like Integrator and LightSampler fill theirs: this file compiling is
// the check that the wrappers match nimbus_guiding_v1_t and nimbus_guiding_v2_t member for member; the
// tests drive the tables as a host or integrator would, without loading a library.
#include <gtest/gtest.h>
#include <nimbus/nimbus.hpp>

#include <nimbus/cpp/photon_guide.hpp>

#include <cstddef>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace guide_wrapper_test {

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

// ---- rev 2: sdk::PhotonGuide ------------------------------------------------------------------------

// Traces `chain + 1` paths of the pass's dims through the tracer and credits the last one.
class ChainGuide final : public nimbus::sdk::PhotonGuide {
 public:
  NIMBUS_DESCRIPTOR("org.nimbus.test.photon-guide", "wrapper guide rev 2", "tests", NIMBUS_KIND_GUIDING, 1, 0,
                    0, nullptr, nullptr)
  nimbus_status_t begin_pass(const nimbus_guide_pass_t &pass) override {
    pass_ = pass;
    return NIMBUS_OK;
  }
  nimbus_status_t run_chain(const nimbus_thread_ctx_t &, uint32_t chain, nimbus::sdk::GuideTracer &tracer,
                            nimbus_guide_totals_t &totals) override {
    if (throw_) throw std::runtime_error("chain failed");
    std::vector<float> u(tracer.dims() + (wrong_length_ ? 1 : 0), 0.5f);
    nimbus::sdk::TracedPath last;
    for (uint32_t i = 0; i <= chain; ++i) {
      last = tracer.trace(u, NIMBUS_GUIDE_UNIFORM);
      totals.uniform_target_sum += last.target;
    }
    tracer.credit(last.path, 2);
    totals.uniform_paths = chain + 1, totals.chain_steps = 2;
    return NIMBUS_OK;
  }
  nimbus_status_t end_pass(const nimbus_guide_totals_t &totals) override {
    ended_steps_ = totals.chain_steps;
    return NIMBUS_OK;
  }

  nimbus_guide_pass_t pass_{};
  uint64_t ended_steps_ = 0;
  bool throw_ = false, wrong_length_ = false;
};

static_assert(std::is_abstract_v<nimbus::sdk::PhotonGuide>, "begin_pass and run_chain must be overridden");

// The integrator's side of a tracer: T = 3 for every path, paths numbered from 10, credits logged.
struct TracerLog {
  uint64_t next = 10;
  std::vector<std::pair<uint64_t, uint64_t>> credits;
};
const nimbus_guide_tracer_t kTracerTemplate = {sizeof(nimbus_guide_tracer_t), 2, nullptr,
                                               [](void *user, const float *, uint32_t, uint64_t *path) {
                                                 *path = static_cast<TracerLog *>(user)->next++;
                                                 return 3.0;
                                               },
                                               [](void *user, uint64_t path, uint64_t m) {
                                                 static_cast<TracerLog *>(user)->credits.emplace_back(path,
                                                                                                      m);
                                               }};

using PhotonLibrary = nimbus::sdk::detail::Library<ChainGuide>;

class PhotonGuideWrapper : public ::testing::Test {
 protected:
  void SetUp() override {
    g_log.clear();
    ASSERT_EQ(PhotonLibrary::entry().create("org.nimbus.test.photon-guide", &kHost, &plugin_), NIMBUS_OK);
    guide_ = static_cast<ChainGuide *>(nimbus::sdk::Plugin::from(plugin_));
    table_ =
        static_cast<const nimbus_guiding_v2_t *>(plugin_->get_interface(plugin_, NIMBUS_IFACE_GUIDING, 2));
    tracer_.user = &log_;
  }
  void TearDown() override { plugin_->destroy(plugin_); }

  const nimbus_plugin_t *plugin_ = nullptr;
  ChainGuide *guide_ = nullptr;
  const nimbus_guiding_v2_t *table_ = nullptr;
  TracerLog log_;
  nimbus_guide_tracer_t tracer_ = kTracerTemplate;
  const nimbus_thread_ctx_t ctx_{sizeof(nimbus_thread_ctx_t), 0, 1, 0, nullptr, 0};
  const nimbus_guide_pass_t pass_{
      {sizeof(nimbus_guide_pass_t), NIMBUS_S_TYPE_GUIDE_PASS, nullptr}, 1, 2, 64, 4, 2};
  // Counts the trampoline must zero before the hook runs.
  nimbus_guide_totals_t totals_{
      {sizeof(nimbus_guide_totals_t), NIMBUS_S_TYPE_GUIDE_TOTALS, nullptr}, 7, 7, 7, 7, 7};
};

TEST_F(PhotonGuideWrapper, ServesOnlyRev2) {
  ASSERT_NE(table_, nullptr);
  EXPECT_EQ(table_->struct_size, sizeof(nimbus_guiding_v2_t));
  EXPECT_EQ(plugin_->get_interface(plugin_, NIMBUS_IFACE_GUIDING, 1), nullptr) << "rev 1 is sdk::Guide's";
  EXPECT_EQ(plugin_->get_interface(plugin_, NIMBUS_IFACE_INTEGRATOR, 1), nullptr);
  EXPECT_EQ(PhotonLibrary::entry().descriptor(0)->kind, NIMBUS_KIND_GUIDING);
}

TEST_F(PhotonGuideWrapper, HooksReachTheVirtualsAndTheTracerReachesTheIntegrator) {
  nimbus_scene_info_t info{};
  info.header = {sizeof info, NIMBUS_S_TYPE_SCENE_INFO, nullptr};
  EXPECT_EQ(table_->prepare(plugin_, &info), NIMBUS_OK) << "default prepare succeeds";
  ASSERT_EQ(table_->begin_pass(plugin_, &pass_), NIMBUS_OK);
  EXPECT_EQ(guide_->pass_.path_budget, 64u);
  ASSERT_EQ(table_->run_chain(plugin_, &ctx_, 2, &tracer_, &totals_), NIMBUS_OK);
  EXPECT_EQ(totals_.header.s_type, NIMBUS_S_TYPE_GUIDE_TOTALS) << "the caller's header is kept";
  EXPECT_EQ(totals_.uniform_paths, 3u);
  EXPECT_EQ(totals_.uniform_target_sum, 9.0) << "summed from zero, not from the caller's 7";
  EXPECT_EQ(totals_.proposals, 0u);
  EXPECT_EQ(totals_.accepted, 0u);
  EXPECT_EQ(log_.credits, (std::vector<std::pair<uint64_t, uint64_t>>{{12, 2}}));
  EXPECT_EQ(table_->end_pass(plugin_, &totals_), NIMBUS_OK);
  EXPECT_EQ(guide_->ended_steps_, 2u);
  EXPECT_TRUE(g_log.empty());
}

TEST_F(PhotonGuideWrapper, NullAndShortStructsAreRefusedBeforeTheHook) {
  EXPECT_EQ(table_->prepare(plugin_, nullptr), NIMBUS_E_INVALID_ARG);
  EXPECT_EQ(table_->begin_pass(plugin_, nullptr), NIMBUS_E_INVALID_ARG);
  nimbus_guide_pass_t short_pass = pass_;
  short_pass.header.struct_size = sizeof(nimbus_struct_header_t) + 8;
  EXPECT_EQ(table_->begin_pass(plugin_, &short_pass), NIMBUS_E_INVALID_ARG);
  EXPECT_EQ(guide_->pass_.path_budget, 0u) << "the hook never ran";
  EXPECT_EQ(table_->run_chain(plugin_, &ctx_, 0, nullptr, &totals_), NIMBUS_E_INVALID_ARG);
  EXPECT_EQ(table_->run_chain(plugin_, &ctx_, 0, &tracer_, nullptr), NIMBUS_E_INVALID_ARG);
  EXPECT_EQ(table_->run_chain(plugin_, nullptr, 0, &tracer_, &totals_), NIMBUS_E_INVALID_ARG);
  nimbus_guide_tracer_t incomplete = tracer_;
  incomplete.trace = nullptr;
  EXPECT_EQ(table_->run_chain(plugin_, &ctx_, 0, &incomplete, &totals_), NIMBUS_E_INVALID_ARG);
  incomplete = tracer_;
  incomplete.struct_size = offsetof(nimbus_guide_tracer_t, credit);
  EXPECT_EQ(table_->run_chain(plugin_, &ctx_, 0, &incomplete, &totals_), NIMBUS_E_INVALID_ARG);
  EXPECT_EQ(table_->end_pass(plugin_, nullptr), NIMBUS_E_INVALID_ARG);
  EXPECT_EQ(log_.next, 10u) << "nothing traced";
}

TEST_F(PhotonGuideWrapper, ExceptionsAreLoggedAndTheChainReportsNothing) {
  guide_->throw_ = true;
  EXPECT_EQ(table_->run_chain(plugin_, &ctx_, 1, &tracer_, &totals_), NIMBUS_E_INTERNAL);
  EXPECT_EQ(totals_.uniform_paths, 0u);
  EXPECT_EQ(totals_.uniform_target_sum, 0.0);
  guide_->throw_ = false, guide_->wrong_length_ = true;
  EXPECT_EQ(table_->run_chain(plugin_, &ctx_, 1, &tracer_, &totals_), NIMBUS_E_INTERNAL);
  EXPECT_EQ(log_.next, 10u) << "a u of the wrong length never reaches the integrator";
  ASSERT_EQ(g_log.size(), 2u);
  EXPECT_EQ(g_log[0], "org.nimbus.test.photon-guide: run_chain: chain failed");
  EXPECT_EQ(g_log[1].rfind("org.nimbus.test.photon-guide: run_chain: trace: ", 0), 0u) << g_log[1];
}

}  // namespace guide_wrapper_test
