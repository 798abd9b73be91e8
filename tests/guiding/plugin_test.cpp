// nimbus.guide.metropolis loaded from its shared library and driven through its C tables, as an integrator
// drives it: what it serves, determinism across chain orders and threads, totals that match what the
// tracer saw, the mutation size's adaptation over passes, the render state of a resumed render, and
// refusals of bad calls.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "loaded_guide.hpp"
#include "toy_targets.hpp"

namespace nimbus::guide_test {
namespace plugin_test {

constexpr uint32_t kDims = 4;
const GaussianBump kBump{0.03};
const Target kBumpTarget = [](std::span<const float> u) { return kBump.at(u); };

TEST(MetropolisGuidePlugin, LoadsAsAGuideServingRev2AndItsRenderState) {
  LoadedGuide g;
  ASSERT_NE(g.plugin(), nullptr);
  ASSERT_NE(g.record(), nullptr);
  EXPECT_EQ(g.record()->kind, NIMBUS_KIND_GUIDING);
  EXPECT_EQ(g.guide().struct_size, sizeof(nimbus_guiding_v2_t));
  const nimbus_plugin_t *p = g.plugin();
  EXPECT_EQ(p->get_interface(p, NIMBUS_IFACE_GUIDING, 1), nullptr) << "rev 1 is not driven by any host";
  EXPECT_EQ(p->get_interface(p, NIMBUS_IFACE_GUIDING, 3), nullptr);
  EXPECT_EQ(p->get_interface(p, NIMBUS_IFACE_INTEGRATOR, 1), nullptr);
  EXPECT_EQ(p->get_interface(p, NIMBUS_IFACE_GUIDING, 2), p->get_interface(p, NIMBUS_IFACE_GUIDING, 2));
}

// A chain's samples depend on (seed, pass, chain) only: two workers running the chains backwards give
// every chain the same paths, targets and credits as one worker running them in order.
TEST(MetropolisGuidePlugin, ChainsAreTheSameInAnyOrderOnAnyThread) {
  LoadedGuide serial, threaded;
  ASSERT_EQ(serial.prepare(), NIMBUS_OK);
  ASSERT_EQ(threaded.prepare(), NIMBUS_OK);
  const nimbus_guide_pass_t pass = guide_pass(11, 1, 64 * 300 + 17, 64, kDims);
  const PassRun a = serial.run_pass(pass, kBumpTarget);
  const PassRun b = threaded.run_pass(pass, kBumpTarget, ChainOrder::reversed_on_two_threads);
  ASSERT_EQ(a.status, NIMBUS_OK);
  ASSERT_EQ(b.status, NIMBUS_OK);
  for (uint32_t c = 0; c < pass.chain_count; ++c) EXPECT_TRUE(a.chains[c] == b.chains[c]) << "chain " << c;
  EXPECT_EQ(a.sum.accepted, b.sum.accepted);
  // ... and the guide's learnt state, hence the next pass, is the same too.
  EXPECT_EQ(serial.save(), threaded.save());
  // Other chains, passes and seeds draw other numbers.
  EXPECT_NE(a.chains[0].u, a.chains[1].u);
  const PassRun next = serial.run_pass(guide_pass(11, 2, pass.path_budget, 64, kDims), kBumpTarget);
  const PassRun other_seed = threaded.run_pass(guide_pass(12, 2, pass.path_budget, 64, kDims), kBumpTarget);
  EXPECT_NE(next.chains[0].u, a.chains[0].u);
  EXPECT_NE(next.chains[0].u, other_seed.chains[0].u);
}

// run_chain's totals are what the tracer saw: the budget split with the remainder on the lowest chains,
// every path counted once, N_u and the sum of T over uniform paths, N_m = the multiplicities credited,
// credits only to paths with T > 0.
TEST(MetropolisGuidePlugin, TotalsAreWhatTheTracerSaw) {
  LoadedGuide g;
  ASSERT_EQ(g.prepare(), NIMBUS_OK);
  const uint32_t chains = 32;
  const uint64_t budget = chains * 500 + 7;
  const PassRun run = g.run_pass(guide_pass(5, 1, budget, chains, kDims), kBumpTarget);
  ASSERT_EQ(run.status, NIMBUS_OK);
  uint64_t traced = 0;
  for (uint32_t c = 0; c < chains; ++c) {
    SCOPED_TRACE("chain " + std::to_string(c));
    const ChainLog &log = run.chains[c];
    const nimbus_guide_totals_t &t = run.totals[c];
    EXPECT_EQ(log.kinds.size(), 500u + (c < 7 ? 1 : 0));
    traced += log.kinds.size();
    uint64_t uniform = 0, proposals = 0, credited = 0;
    double uniform_sum = 0;
    for (size_t i = 0; i < log.kinds.size(); ++i) {
      if (log.kinds[i] == NIMBUS_GUIDE_UNIFORM) {
        ++uniform, uniform_sum += log.targets[i];
      } else {
        EXPECT_EQ(log.kinds[i], NIMBUS_GUIDE_PROPOSAL);
        ++proposals;
      }
    }
    for (const auto &[path, m] : log.credits) {
      ASSERT_LT(path, log.kinds.size());
      EXPECT_GT(log.targets[path], 0.0);
      EXPECT_GT(m, 0u);
      credited += m;
    }
    EXPECT_EQ(t.uniform_paths, uniform);
    EXPECT_EQ(t.proposals, proposals);
    EXPECT_DOUBLE_EQ(t.uniform_target_sum, uniform_sum);
    EXPECT_EQ(t.chain_steps, credited);
    EXPECT_EQ(t.chain_steps, proposals) << "one mutation a step";
    EXPECT_LE(t.accepted, t.proposals);
    EXPECT_GT(t.accepted, 0u);
  }
  EXPECT_EQ(traced, budget);
}

// The spec's adaptation test on a 4-D Gaussian bump: d starts at 0.05, where 0.55 of the mutations are
// accepted, and end_pass moves it until the acceptance lies in [0.2, 0.4] (it tends to 0.234). 256
// chains x 200 paths a pass make the acceptance's sd ~ 0.005.
TEST(MetropolisGuidePlugin, AdaptationBringsTheAcceptanceIntoRange) {
  LoadedGuide g;
  ASSERT_EQ(g.prepare(), NIMBUS_OK);
  for (uint64_t pass = 1; pass <= 10; ++pass) {
    const PassRun run = g.run_pass(guide_pass(3, pass, 256 * 200, 256, kDims), kBumpTarget);
    ASSERT_EQ(run.status, NIMBUS_OK);
    std::printf("pass %llu: acceptance %.3f\n", (unsigned long long)pass, run.acceptance());
    if (pass == 1) {
      EXPECT_GT(run.acceptance(), 0.45) << "the start must be off, or adaptation shows nothing";
    }
    if (pass >= 5) {
      EXPECT_GE(run.acceptance(), 0.2) << "pass " << pass;
      EXPECT_LE(run.acceptance(), 0.4) << "pass " << pass;
    }
  }
}

// Calls an integrator must not make are refused with a status, not undefined behaviour.
TEST(MetropolisGuidePlugin, RefusesBadCalls) {
  LoadedGuide g;
  ASSERT_EQ(g.prepare(), NIMBUS_OK);
  const nimbus_plugin_t *p = g.plugin();
  const nimbus_guiding_v2_t &t = g.guide();
  nimbus_guide_totals_t totals{{sizeof totals, NIMBUS_S_TYPE_GUIDE_TOTALS, nullptr}, 0, 0, 0, 0, 0};
  EXPECT_EQ(t.end_pass(p, &totals), NIMBUS_E_INVALID_ARG) << "no pass begun";
  EXPECT_EQ(t.begin_pass(p, nullptr), NIMBUS_E_INVALID_ARG);
  nimbus_guide_pass_t pass = guide_pass(1, 1, 100, 0, kDims);
  EXPECT_EQ(t.begin_pass(p, &pass), NIMBUS_E_INVALID_ARG) << "no chains";
  pass = guide_pass(1, 0, 100, 4, kDims);
  EXPECT_EQ(t.begin_pass(p, &pass), NIMBUS_E_INVALID_ARG) << "passes are 1-based";
  pass = guide_pass(1, 1, 100, 4, kDims);
  pass.header.struct_size = sizeof(nimbus_struct_header_t);
  EXPECT_EQ(t.begin_pass(p, &pass), NIMBUS_E_INVALID_ARG) << "a short struct";

  pass = guide_pass(1, 2, 100, 4, kDims);
  ASSERT_EQ(t.begin_pass(p, &pass), NIMBUS_OK);
  ChainLog log{&kBumpTarget, kDims};
  const nimbus_thread_ctx_t ctx{sizeof ctx, 0, 1, 0, nullptr, 0};
  nimbus_guide_tracer_t tracer{sizeof tracer, kDims, &log, log_trace, log_credit};
  EXPECT_EQ(t.run_chain(p, &ctx, 4, &tracer, &totals), NIMBUS_E_INVALID_ARG) << "no chain 4";
  EXPECT_EQ(t.run_chain(p, &ctx, 0, &tracer, nullptr), NIMBUS_E_INVALID_ARG);
  EXPECT_EQ(t.run_chain(p, &ctx, 0, nullptr, &totals), NIMBUS_E_INVALID_ARG);
  tracer.dims = kDims - 1;
  EXPECT_EQ(t.run_chain(p, &ctx, 0, &tracer, &totals), NIMBUS_E_INVALID_ARG)
      << "another dims than the pass's";
  tracer.dims = kDims, tracer.credit = nullptr;
  EXPECT_EQ(t.run_chain(p, &ctx, 0, &tracer, &totals), NIMBUS_E_INVALID_ARG) << "an incomplete tracer";
  EXPECT_TRUE(log.kinds.empty()) << "nothing traced by refused calls";
  tracer.credit = log_credit;
  EXPECT_EQ(t.run_chain(p, &ctx, 0, &tracer, &totals), NIMBUS_OK);
  EXPECT_EQ(log.kinds.size(), 25u);
  EXPECT_EQ(t.end_pass(p, &totals), NIMBUS_OK);
  pass = guide_pass(1, 1, 100, 4, kDims);
  EXPECT_EQ(t.begin_pass(p, &pass), NIMBUS_E_INVALID_ARG) << "pass 1 after pass 2";
  EXPECT_FALSE(g.messages().empty());
}

}  // namespace plugin_test
}  // namespace nimbus::guide_test
