// Walker/Vose alias table: O(1) sampling of a discrete distribution, used for picking triangles of an
// emitter by area and lights by power. Header-only so plugins can use it too (no ABI crossing).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace nimbus {

class AliasTable {
 public:
  AliasTable() = default;
  // Weights must be finite and >= 0. All-zero weights leave an empty table (sample returns -1).
  explicit AliasTable(const std::vector<double> &weights) {
    const size_t n = weights.size();
    double sum = 0;
    for (double w : weights) sum += w;
    if (n == 0 || !(sum > 0)) return;
    bins_.resize(n);
    std::vector<double> scaled(n);
    std::vector<uint32_t> small, large;
    for (size_t i = 0; i < n; ++i) {
      bins_[i].pmf = float(weights[i] / sum);
      scaled[i] = weights[i] / sum * double(n);
      (scaled[i] < 1.0 ? small : large).push_back(uint32_t(i));
    }
    while (!small.empty() && !large.empty()) {
      const uint32_t s = small.back(), l = large.back();
      small.pop_back();
      bins_[s].q = float(scaled[s]);
      bins_[s].alias = l;
      scaled[l] = (scaled[l] + scaled[s]) - 1.0;
      if (scaled[l] < 1.0) {
        large.pop_back();
        small.push_back(l);
      }
    }
    // Leftovers are 1 up to rounding.
    for (uint32_t i : large) bins_[i].q = 1, bins_[i].alias = i;
    for (uint32_t i : small) bins_[i].q = 1, bins_[i].alias = i;
    // sample() draws the in-bin number from the fraction of u * n, and u has 24 bits (the renderer's
    // random floats): within bin i that fraction takes the values (r_i + j n) / 2^24, j = 0, 1, ... A
    // threshold q below those steps is met at the rate of a whole step while its sample is weighted by
    // the far smaller pmf (lights 1e9 apart in power: ~60x too bright). So the pmfs are counted from
    // the table itself over all 2^24 values of u: the pmf returned is the rate at which sample() picks.
    constexpr uint64_t kGrid = uint64_t(1) << 24;
    std::vector<double> pmf(n, 0.0);
    for (size_t i = 0; i < n; ++i) {
      const uint64_t m_lo = (uint64_t(i) * kGrid + n - 1) / n, m_end = (uint64_t(i + 1) * kGrid + n - 1) / n;
      if (m_end <= m_lo) continue;  // more bins than values of u: never reached
      const double in_bin = double(m_end - m_lo), r_lo = double(m_lo * n - uint64_t(i) * kGrid);
      const double q_grid = double(bins_[i].q) * double(kGrid);
      const double kept = q_grid <= r_lo ? 0 : std::min(in_bin, std::ceil((q_grid - r_lo) / double(n)));
      pmf[i] += kept / double(kGrid);
      pmf[bins_[i].alias] += (in_bin - kept) / double(kGrid);
    }
    for (size_t i = 0; i < n; ++i) bins_[i].pmf = float(pmf[i]);
  }

  bool empty() const { return bins_.empty(); }
  size_t size() const { return bins_.size(); }
  float pmf(size_t i) const { return i < bins_.size() ? bins_[i].pmf : 0.0f; }

  // u in [0,1). Returns the index (or -1 for an empty table) and its probability; *u_remapped (optional)
  // receives a fresh uniform number in [0,1) derived from u, so one number can pick and then place.
  int64_t sample(float u, float *pmf_out = nullptr, float *u_remapped = nullptr) const {
    if (bins_.empty()) {
      if (pmf_out) *pmf_out = 0;
      return -1;
    }
    const double x = double(u) * double(bins_.size());
    size_t i = std::min(size_t(x), bins_.size() - 1);
    const float up = float(x - double(i));  // reuse the fraction as the second random number
    const bool keep = up < bins_[i].q;
    const size_t chosen = keep ? i : bins_[i].alias;
    if (pmf_out) *pmf_out = bins_[chosen].pmf;
    if (u_remapped) {
      const float r = keep ? up / bins_[i].q : (up - bins_[i].q) / (1 - bins_[i].q);
      *u_remapped = std::min(r, 0x1.fffffep-1f);
    }
    return int64_t(chosen);
  }

 private:
  struct Bin {
    float q = 1, pmf = 0;
    uint32_t alias = 0;
  };
  std::vector<Bin> bins_;
};

}  // namespace nimbus
