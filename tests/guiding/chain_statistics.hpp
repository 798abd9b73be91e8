// Statistics of Markov chain output for the stationarity tests: the integrated autocorrelation time, by
// which samples are thinned until they are nearly independent, and histograms of the thinned samples.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

namespace nimbus::guide_test {

// tau = 1 + 2 sum_k rho_k of f(state) over independent chains of equal law: N correlated samples carry
// the information of N / tau independent ones. The sum stops at Sokal's automatic window, the first lag
// M >= 5 tau(M) (later lags add noise, not signal). Autocovariances pool every `every`-th chain around
// the pooled mean; lag pairs never straddle two chains.
inline double integrated_autocorrelation_time(const std::vector<std::vector<float>> &chains,
                                              const std::function<double(float)> &f, size_t every = 1) {
  std::vector<std::vector<double>> x;
  double mean = 0, n = 0;
  for (size_t c = 0; c < chains.size(); c += every) {
    x.emplace_back(chains[c].size());
    for (size_t t = 0; t < chains[c].size(); ++t) mean += x.back()[t] = f(chains[c][t]), ++n;
  }
  if (n < 2) return 1;
  mean /= n;
  double var = 0;
  for (std::vector<double> &c : x)
    for (double &v : c) v -= mean, var += v * v;
  var /= n;
  if (var <= 0) return 1;
  double tau = 1;
  for (size_t lag = 1;; ++lag) {
    double cov = 0, pairs = 0;
    for (const std::vector<double> &c : x) {
      for (size_t t = 0; t + lag < c.size(); ++t) cov += c[t] * c[t + lag];
      pairs += c.size() > lag ? double(c.size() - lag) : 0;
    }
    if (pairs == 0) return tau;
    tau += 2 * cov / pairs / var;
    if (double(lag) >= 5 * tau) return std::max(tau, 1.0);
  }
}

// Counts of every `stride`-th sample of each chain (from its first) in `bins` equal bins of [0, 1).
inline std::vector<double> thinned_histogram(const std::vector<std::vector<float>> &chains, size_t stride,
                                             int bins) {
  std::vector<double> counts(bins, 0.0);
  for (const std::vector<float> &c : chains)
    for (size_t t = 0; t < c.size(); t += stride) ++counts[std::min(bins - 1, int(c[t] * float(bins)))];
  return counts;
}

}  // namespace nimbus::guide_test
