// The stationarity check of caustics-solver.md §10 (iv): do a pass's chain states follow the spiky target's
// T/b? A 40-bin chi-square test on the states thinned by their measured integrated autocorrelation time.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "chain_statistics.hpp"
#include "chi_square.hpp"
#include "toy_targets.hpp"

namespace nimbus::guide_test {

struct SpikyFit {
  double tau = 0;              // integrated autocorrelation time: the larger of u's and the spike indicator's
  size_t stride = 0;           // thinning: every stride-th state of each chain
  double thinned = 0;          // samples in the histogram
  double outside_support = 0;  // thinned states where T = 0: a state always has T > 0
  test::ChiSquareResult chi2;
};

// `states`: per chain, the state's u after every step.
inline SpikyFit fit_spiky_target(const std::vector<std::vector<float>> &states) {
  constexpr int kBins = 40;
  SpikyFit r;
  // From every 8th chain: 32 chains x 10^4 steps give tau within a few per cent, at an eighth of the cost.
  const double tau_u = integrated_autocorrelation_time(
      states, [](float u) { return double(u); }, 8);
  const double tau_spike = integrated_autocorrelation_time(
      states, [](float u) { return u >= 0.95f ? 1.0 : 0.0; }, 8);
  r.tau = std::max(tau_u, tau_spike);
  r.stride = size_t(std::ceil(r.tau));
  const std::vector<double> observed = thinned_histogram(states, r.stride, kBins);
  for (double o : observed) r.thinned += o;
  std::vector<double> expected(kBins);
  const double b = SpikyTarget::normalisation();
  for (int i = 0; i < kBins; ++i) {
    expected[i] = r.thinned * SpikyTarget::integral(double(i) / kBins, double(i + 1) / kBins) / b;
    if (expected[i] == 0) r.outside_support += observed[i];
  }
  // Bins expecting nothing (T = 0 there) hold nothing either when outside_support is 0: they pool into an
  // empty category that adds no term.
  r.chi2 = test::chi_square_counts(observed, expected, 5);
  return r;
}

}  // namespace nimbus::guide_test
