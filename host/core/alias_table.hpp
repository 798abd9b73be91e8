// Walker/Vose alias table: O(1) sampling of a discrete distribution, used for picking triangles of an
// emitter by area and lights by power. Header-only so plugins can use it too (no ABI crossing).
#pragma once

#include <algorithm>
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
