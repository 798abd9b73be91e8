// caustics-solver.md §10 (iv), Metropolis stationarity: the production chain code (exchange and an
// always-run mutation, d fixed) on the 1-D spiky target, 256 chains x 10^4 steps per seed. The states,
// each counted for every step it was kept (its credited multiplicity), must follow T/b by a chi-square
// test on samples thinned by the measured integrated autocorrelation time; the mixture estimator of
// nimbus/guiding.h's contract must find a known integral and b. HJ11's variant (no mutation in a step
// whose exchange succeeded) must fail the same chi-square test.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "chain_record.hpp"
#include "spiky_fit.hpp"
#include "toy_targets.hpp"

namespace nimbus::guide_test {
namespace stationarity_test {

constexpr uint32_t kChains = 256;
constexpr uint64_t kSteps = 10'000;
constexpr uint64_t kSeeds = 20;
// Where end_pass's adaptation settles for this target: the acceptance is 0.37 > 0.234 even at the upper
// clamp. The skipped mutation's bias grows with the mutation's reach, so this d also shows it best.
constexpr double kMutationSize = 0.5;

ChainSettings settings(bool skip_mutation_after_swap) {
  // Two paths a step, plus the start's draws: about 26 until 16 hit, as P(T > 0) = 0.61.
  return {2 * kSteps + 26, kMutationSize, skip_mutation_after_swap};
}

struct SeedResult {
  SpikyFit fit;
  double b_hat = 0;
  double g_estimate = 0;  // the mixture estimator of the integral of SpikyIntegrand
};

SeedResult run_seed(uint64_t seed, bool skip_mutation_after_swap) {
  const OneDimensionalPass pass =
      run_one_dimensional(SpikyTarget::at, seed, kChains, settings(skip_mutation_after_swap));
  SeedResult r;
  r.fit = fit_spiky_target(pass.states);
  // The contract's estimator: a path weighs (1[uniform] + m) / (N_u + N_m T / b^).
  const ChainTotals &t = pass.totals;
  r.b_hat = t.uniform_target_sum / double(t.uniform_paths);
  for (const OneDimensionalPass::Weighted &w : pass.weighted)
    r.g_estimate += SpikyIntegrand::at(w.u) * double(w.count) /
                    (double(t.uniform_paths) + double(t.chain_steps) * SpikyTarget::at(w.u) / r.b_hat);
  return r;
}

void print(const char *what, uint64_t seed, const SeedResult &r) {
  std::printf(
      "%s seed %2llu: tau %.1f, %.0f thinned states, chi2 %.1f (%d dof) p %.3g, b^ %+.3f %%, g %+.3f %%\n",
      what, (unsigned long long)seed, r.fit.tau, r.fit.thinned, r.fit.chi2.statistic, r.fit.chi2.dof,
      r.fit.chi2.p_value, 100 * (r.b_hat / SpikyTarget::normalisation() - 1),
      100 * (r.g_estimate / SpikyIntegrand::integral() - 1));
}

// One test for the three checks on the same 20 runs: ctest runs every test in a process of its own, and
// the runs are the expensive part.
TEST(GuideStationarity, SpikyTargetStatesEstimatorAndNormalisation) {
  int passed = 0;
  for (uint64_t seed = 1; seed <= kSeeds; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const SeedResult r = run_seed(seed, false);
    print("exchange + mutation", seed, r);
    // The states: T/b by chi-square, for 19 of the 20 seeds at p > 0.01; none where T = 0. Thinning must
    // leave enough samples for a test that can see a bias (~10^5).
    ASSERT_TRUE(r.fit.chi2.error.empty()) << r.fit.chi2.error;
    EXPECT_EQ(r.fit.outside_support, 0) << "a state where T = 0";
    EXPECT_GT(r.fit.thinned, 5e4) << "tau " << r.fit.tau;
    passed += r.fit.chi2.p_value > 0.01;

    // b^ = (sum of T over uniform paths) / N_u with N_u ~ 2.57e6 (a uniform path per step and the start's
    // draws) and sd(T) / b = 2.730 for uniform u: sd(b^) / b = 2.730 / sqrt(2.57e6) = 0.17 %, so 1 % is
    // 5.9 sd.
    EXPECT_NEAR(r.b_hat / SpikyTarget::normalisation(), 1.0, 0.01);

    // The estimate is (1/N) sum over uniform paths of h plus (1/N) sum over chain steps of h, h = g / (1 +
    // T/b), N = 2.56e6 of each. h has sd 2.63 for uniform u and 5.50 for u ~ T/b (quadrature); with the
    // chain's tau ~ 20 that is sd 0.13 % of the integral 12.0 (the 20 seeds spread by 0.19 %): 1 % is 5
    // sd. Weights that credit each state once instead of m times, or leave out T / b^, miss by 45 % or
    // more.
    EXPECT_NEAR(r.g_estimate / SpikyIntegrand::integral(), 1.0, 0.01);
  }
  EXPECT_GE(passed, 19) << "seeds of " << kSeeds << " passed the chi-square test";
}

// HJ11 skip the mutation when the exchange succeeded; with a graded T that biases the states towards
// what the exchange brings in. The criterion above tolerates one failing seed in 20, so two failing
// seeds fail it; they fail by far (measured p ~ 1e-100), not by the luck of a seed.
TEST(GuideStationaritySkip, SkippingTheMutationAfterASwapFailsTheChiSquareTest) {
  for (uint64_t seed = 1; seed <= 2; ++seed) {
    const SeedResult r = run_seed(seed, true);
    ASSERT_TRUE(r.fit.chi2.error.empty()) << r.fit.chi2.error;
    print("skip after swap", seed, r);
    EXPECT_LT(r.fit.chi2.p_value, 1e-6) << "seed " << seed;
  }
}

}  // namespace stationarity_test
}  // namespace nimbus::guide_test
