// Russian roulette of photon lookups (solver spec 5): a camera path looks photons up at a rough vertex
// with probability q, and a lookup that happens counts 1/q times. A lookup costs its kd-tree descent
// whether or not it finds a photon, and behind a diffuse bounce lookups are incoherent (cache misses)
// and most find little of the image's light. q is chosen for the lookups behind the path's first rough
// vertex to minimise error x time, from what the solver measures: the merges' second moment per class and
// the work of each class's lookups. Lookups at the first rough vertex always happen (q = 1): they carry the
// caustics the camera sees directly, which under delta lights nothing but merges renders, and a second
// moment measured from few lookups is heavy-tailed and underestimated, so a low q would hold itself down
// (docs/performance.md section 5). The merge technique keeps its density q times the photon density in every
// MIS weight (merging.cpp, mis.hpp), so the estimate stays unbiased and the weights a partition of unity at
// any q.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace nimbus::caustics {

// Classes of lookup vertex: the camera path's first rough vertex, and every rough vertex after it.
enum LookupClass : uint32_t { kFirstLookup = 0, kLaterLookup = 1, kLookupClasses = 2 };
inline LookupClass lookup_class(uint32_t rough_count) {
  return rough_count <= 1 ? kFirstLookup : kLaterLookup;
}

// The merge technique's density in MIS at a lookup, besides q: a quarter per rough vertex between it and
// the camera path's first rough vertex. Two merges of one path separated by a diffuse bounce have equal
// pdfs, but the later one sees a caustic's peak through that bounce while the earlier one's kernel
// averages it: with the pdfs alone the later merge keeps half the weight or more and a dark wall's pixel
// takes a bright caustic's value (a camera path from a table via a wall into the focus under a glass ball,
// docs/performance.md sections 5 and 9). Any factor both sides give a technique keeps the weights a
// partition of unity (the photon side applies it per rough vertex, mis.hpp); 1/4 is measured there at
// equal time.
inline constexpr float kLaterLookupMisFactor = 0.25f;
// That factor at the lookup vertex with `rough_count` rough vertices up to it (1: the first), in double:
// long paths take it far below float's range. A product, not std::pow: every camera vertex asks, and
// paths have a few rough vertices.
inline double lookup_rank_factor(uint32_t rough_count) {
  double f = 1;
  for (uint32_t n = 1; n < rough_count; ++n) f *= kLaterLookupMisFactor;
  return f;
}

// The lowest lookup probability: the second moment is measured from the lookups that happen (q Y^2 per
// lookup, an unbiased estimate at any q), and below this too few happen in a window to measure it.
inline constexpr float kMinLookupProbability = 1.0f / 16;

// What the solver measured over the last iterations, per camera path: the relative variance of a sample
// (relMSE weights, useful_pixels.hpp), the second moment each class's lookups would have at q = 1, the
// work of everything but the lookups (camera paths and their share of the photon pass) and the work of
// each class's lookups at its current q.
struct RouletteSample {
  double variance = 0;
  std::array<double, kLookupClasses> second_moment{};
  double other_work = 0;
  std::array<double, kLookupClasses> lookup_work{};
};

class LookupRoulette {
 public:
  float probability(LookupClass c) const { return q_[c]; }
  const std::array<float, kLookupClasses> &probabilities() const { return q_; }

  // The later class's probability that minimises (V_o + sum M_c / q_c) (W_o + sum q_c w_c), V_o and W_o the
  // variance and work without lookups, M_c and w_c a class's second moment and work at q = 1: at the
  // optimum q_c = sqrt(M_c W / (V w_c)), W and V the totals. Each update takes that step from the current
  // totals (a fixed-point iteration of the optimum), smoothed in log space: the variances are noisy.
  void update(const RouletteSample &s) {
    double work = s.other_work;
    for (double w : s.lookup_work) work += w;
    if (!(s.variance > 0) || !(work > 0)) return;
    for (uint32_t c = kLaterLookup; c < kLookupClasses; ++c) {
      const double w1 = s.lookup_work[c] / q_[c];  // the class's work at q = 1
      if (!(w1 > 0)) continue;                     // no lookup happened: nothing learnt
      const double target = std::sqrt(std::max(0.0, s.second_moment[c]) * work / (s.variance * w1));
      const float q = float(std::clamp(target, double(kMinLookupProbability), 1.0));
      q_[c] = std::exp(0.5f * (std::log(q_[c]) + std::log(q)));
    }
  }

  template <class Writer>
  void save(Writer &w) const {
    w.put(q_);
  }
  template <class Reader>
  bool restore(Reader &r) {
    std::array<float, kLookupClasses> q{};
    if (!r.get(q)) return false;
    for (float v : q)
      if (!(v >= kMinLookupProbability && v <= 1)) return false;
    q_ = q;
    q_[kFirstLookup] = 1;  // never rouletted (a state saved by an older solver may hold less)
    return true;
  }

 private:
  std::array<float, kLookupClasses> q_{1.0f, 1.0f};
};

}  // namespace nimbus::caustics
