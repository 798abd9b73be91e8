// The chain's mechanics (metropolis_chain.hpp) driven directly: budget shares, the order of the paths it
// traces (start, then a uniform path and a mutation per step), uniform-only chains, the perturbation, and
// random numbers that depend on (seed, pass, chain) alone.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "chain_record.hpp"
#include "toy_targets.hpp"

namespace nimbus::guide_test {
namespace chain_test {

using guide::chain_budget;
using guide::chain_stream;
using guide::MetropolisChain;

const auto kSpiky = [](std::span<const float> u) { return SpikyTarget::at(u[0]); };

template <class Target>
RecordingTracer<Target> run_chain(const Target &target, const ChainSettings &s, nimbus_rng_t rng,
                                  ChainTotals *totals = nullptr, uint32_t dims = 1) {
  RecordingTracer tracer(target, dims);
  MetropolisChain chain(s, dims, rng, tracer);
  const ChainTotals t = chain.run();
  if (totals) *totals = t;
  return tracer;
}

TEST(GuideChain, BudgetSharesAddUpWithTheRemainderOnTheLowestChains) {
  uint64_t sum = 0;
  for (uint32_t c = 0; c < 256; ++c) {
    EXPECT_EQ(chain_budget(1000, 256, c), c < 1000 % 256 ? 4u : 3u);
    sum += chain_budget(1000, 256, c);
  }
  EXPECT_EQ(sum, 1000u);
  EXPECT_EQ(chain_budget(100, 256, 99), 1u);
  EXPECT_EQ(chain_budget(100, 256, 100), 0u);
  EXPECT_EQ(chain_budget(100, 256, 256), 0u) << "no such chain";
  EXPECT_EQ(chain_budget(100, 0, 0), 0u);
}

// Uniform paths until 16 hit; then per step a uniform path and a proposal; an odd path left over is
// uniform. Each traced path counts once against the budget; the steps' multiplicities are all credited.
TEST(GuideChain, TracesItsBudgetInTheSpecsOrder) {
  ChainTotals t;
  const auto tracer = run_chain(kSpiky, {1001, 0.05}, chain_stream(1, 1, 0), &t);
  ASSERT_EQ(tracer.kinds.size(), 1001u);
  size_t start = 0;
  for (int hits = 0; hits < 16; ++start) {
    ASSERT_EQ(tracer.kinds[start], NIMBUS_GUIDE_UNIFORM);
    hits += SpikyTarget::at(tracer.u[start]) > 0;
  }
  const uint64_t steps = (1001 - start) / 2;
  for (size_t i = start; i + 1 < start + 2 * steps; i += 2) {
    EXPECT_EQ(tracer.kinds[i], NIMBUS_GUIDE_UNIFORM) << i;
    EXPECT_EQ(tracer.kinds[i + 1], NIMBUS_GUIDE_PROPOSAL) << i;
  }
  if ((1001 - start) % 2 == 1) {
    EXPECT_EQ(tracer.kinds.back(), NIMBUS_GUIDE_UNIFORM) << "the odd path left over";
  }
  EXPECT_EQ(t.chain_steps, steps);
  EXPECT_EQ(t.proposals, steps);
  EXPECT_EQ(t.uniform_paths, 1001 - steps);
  const auto states = tracer.state_paths();
  EXPECT_EQ(states.size(), steps) << "every step credited once";
  for (uint64_t p : states) EXPECT_GT(SpikyTarget::at(tracer.u[p]), 0);
}

TEST(GuideChain, WithoutAHitInTheStartTheChainStaysUniform) {
  ChainTotals t;
  const auto nothing = [](std::span<const float>) { return 0.0; };
  const auto tracer = run_chain(nothing, {1000, 0.05}, chain_stream(1, 1, 0), &t);
  EXPECT_EQ(tracer.kinds.size(), 1000u);
  for (uint32_t k : tracer.kinds) EXPECT_EQ(k, NIMBUS_GUIDE_UNIFORM);
  EXPECT_EQ(t.uniform_paths, 1000u);
  EXPECT_EQ(t.chain_steps, 0u);
  EXPECT_TRUE(tracer.credits.empty());
  // A target that is negative, NaN or infinite counts as 0: never a state.
  const auto broken = [](std::span<const float> u) {
    return u[0] < 0.5f ? -1.0 : (u[0] < 0.75f ? std::nan("") : INFINITY);
  };
  const auto b = run_chain(broken, {500, 0.05}, chain_stream(2, 1, 0), &t);
  EXPECT_TRUE(b.credits.empty());
  EXPECT_EQ(t.uniform_target_sum, 0.0);
}

TEST(GuideChain, ABudgetTooSmallToStepEndsAfterTheStart) {
  ChainTotals t;
  const auto tracer = run_chain(kSpiky, {5, 0.05}, chain_stream(1, 1, 0), &t);
  EXPECT_EQ(tracer.kinds.size(), 5u);
  EXPECT_EQ(t.uniform_paths, 5u);
  EXPECT_EQ(t.chain_steps, 0u);
  EXPECT_TRUE(tracer.credits.empty());
}

// Determinism: the numbers come from (seed, pass, chain) alone, so a chain run again, after other chains
// or alone, traces the same u's; each key changes them.
TEST(GuideChain, SamePassKeysSamePaths) {
  const ChainSettings s{400, 0.05};
  const auto first = run_chain(kSpiky, s, chain_stream(7, 3, 5));
  for (uint32_t c = 0; c < 5; ++c) run_chain(kSpiky, s, chain_stream(7, 3, c));
  const auto again = run_chain(kSpiky, s, chain_stream(7, 3, 5));
  EXPECT_EQ(first.u, again.u);
  EXPECT_EQ(first.kinds, again.kinds);
  EXPECT_EQ(first.credits, again.credits);
  EXPECT_NE(first.u, run_chain(kSpiky, s, chain_stream(8, 3, 5)).u);
  EXPECT_NE(first.u, run_chain(kSpiky, s, chain_stream(7, 4, 5)).u);
  EXPECT_NE(first.u, run_chain(kSpiky, s, chain_stream(7, 3, 6)).u);
}

// u +- xi^(1 + 1/d), wrapped: always in [0, 1), either sign equally often. From u = 1/2 a step delta > 1/2
// wraps, so the distance moved is min(delta, 1 - delta), whose mean for delta = xi^a is E[delta] - E[(2
// delta - 1) 1{delta > 1/2}] = 1/(a + 1) - 2 (1 - c^(a + 1)) / (a + 1) + (1 - c), c = 2^(-1/a).
TEST(GuideChain, PerturbationIsSymmetricAndWraps) {
  nimbus_rng_t rng = chain_stream(1, 1, 1);
  const double d = 0.1, a = 1 + 1 / d, c = std::pow(2.0, -1 / a);
  const double mean_distance = 1 / (a + 1) - 2 * (1 - std::pow(c, a + 1)) / (a + 1) + (1 - c);
  const int n = 200'000;
  double sum = 0, sum2 = 0;
  int up = 0, moved = 0;
  for (int i = 0; i < n; ++i) {
    const double step = double(guide::perturbed(0.5f, a, rng)) - 0.5;
    sum += std::abs(step), sum2 += step * step;
    if (step != 0) ++moved, up += step > 0;
    for (float edge : {0.0f, std::nextafter(1.0f, 0.0f)}) {
      const float w = guide::perturbed(edge, a, rng);
      ASSERT_GE(w, 0.0f);
      ASSERT_LT(w, 1.0f);
    }
  }
  // Within 5 sd of the sample mean (sd ~ 2.6e-4 for n = 2e5).
  EXPECT_NEAR(sum / n, mean_distance, 5 * std::sqrt(sum2 / n - (sum / n) * (sum / n)) / std::sqrt(n));
  // Signs: binomial(moved, 1/2), sd sqrt(moved) / 2.
  EXPECT_NEAR(up, moved / 2.0, 5 * std::sqrt(double(moved)) / 2);
}

// The test-only switch: after a successful exchange the step traces no mutation, so such a step shows
// two uniform paths in a row; without the switch every step has its mutation.
TEST(GuideChain, SkipSwitchDropsTheMutationOnlyAfterASwap) {
  ChainTotals with, without;
  run_chain(kSpiky, {4000, 0.3, false}, chain_stream(1, 1, 0), &without);
  run_chain(kSpiky, {4000, 0.3, true}, chain_stream(1, 1, 0), &with);
  EXPECT_EQ(without.proposals, without.chain_steps);
  EXPECT_LT(with.proposals, with.chain_steps);
  EXPECT_GT(with.proposals, with.chain_steps / 2) << "an exchange succeeds in a minority of steps";
}

}  // namespace chain_test
}  // namespace nimbus::guide_test
