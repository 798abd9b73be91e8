// Whether light paths pay on this scene (light_paths.hpp): an equal-time comparison the render runs on
// itself. Light tracing shares its paths with path tracing, merges and splats through MIS, which weighs
// densities and not variances, so no model of how shares shift when it is added predicts its worth: in
// a closed room under a point light it renders the indirect light 4x better at equal time, on a glass
// on an open floor it adds cost and little else. The first kTrialIterations camera passes with a map
// trace light paths, and every sample also carries its light as the same paths would have brought it
// without them (each contribution times its MIS weight without light paths over its weight with them:
// exactly the pass without them, on the same random numbers). Each pixel's light per pass, with (camera
// sample and every splat into it) and without (the same, light paths' splats left out), gives both
// arms' relative variance per pass, weighted as relMSE weighs it, from the same passes; the work per
// pass with and without the light paths' share their cost. Light paths stay when variance times work
// is lower with them; no pass of the render goes without them to find out.
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "useful_pixels.hpp"

namespace nimbus::caustics {

// Passes measured before the decision. The mean over the pixels of each pixel's variance is unbiased
// from two samples on; four give the same decisions as eight on every scene measured (docs/performance.md
// §5), and on scenes where light paths do not pay each pass of the trial costs its light paths' work.
inline constexpr uint32_t kTrialIterations = 4;
// After kEarlyIterations passes the trial decides when variance times work differs by more than the
// factor kEarlyMargin either way: from the second pass to the eighth that product moved by at most 19 %
// on every scene measured, and never across 1 from beyond this margin.
inline constexpr uint32_t kEarlyIterations = 2;
inline constexpr double kEarlyMargin = 1.25;

class LightPathTrial {
 public:
  enum class State : uint8_t { Trial = 0, On = 1, Off = 2 };

  // [main-thread] A new render of `pixels` pixels; possible: light paths can be traced at all.
  void reset(size_t pixels, bool possible) {
    state_ = possible ? State::Trial : State::Off;
    sums_.assign(possible ? pixels : 0, Sums{});
    passes_ = 0, work_[0] = work_[1] = 0;
  }
  State state() const { return state_; }
  // Whether passes trace light paths (on trial, they do).
  bool light_paths() const { return state_ != State::Off; }
  bool measuring() const { return state_ == State::Trial; }

  // [main-thread] Light (luminance) splatted into pixel i before this pass's camera samples, with light
  // paths and as it would have been without them.
  void add_splat(size_t i, float with, float without) {
    if (measuring() && i < sums_.size()) sums_[i].pending[1] += with, sums_[i].pending[0] += without;
  }
  // [render-thread] Pixel i's camera sample, with light paths and without (each pixel belongs to one
  // tile: no two threads meet).
  void add_sample(size_t i, float with, float without) {
    if (!measuring() || i >= sums_.size()) return;
    Sums &s = sums_[i];
    const float v[2] = {without + s.pending[0], with + s.pending[1]};
    s.pending[0] = s.pending[1] = 0;
    s.n += 1;
    for (int a = 0; a < 2; ++a) s.sum[a] += v[a], s.sum2[a] += v[a] * v[a];
  }

  // [main-thread] A measured pass ended: its work units per camera path, all included, and the light
  // paths' share of them. Decides after kEarlyIterations passes when the arms are far apart, else after
  // kTrialIterations.
  void pass_done(double work, double light_path_work) {
    if (!measuring()) return;
    work_[0] += work - light_path_work, work_[1] += work;
    if (++passes_ < kEarlyIterations) return;
    const double v_off = variance(0), v_on = variance(1);
    const double c_off = work_[0] / passes_, c_on = work_[1] / passes_;
    const double off = v_off * c_off, on = v_on * c_on;
    const bool clear = on * kEarlyMargin < off || off * kEarlyMargin < on;
    if (passes_ < kTrialIterations && !clear) return;
    state_ = on < off ? State::On : State::Off;
    decision_ = {v_off, v_on, c_off, c_on};
    sums_ = std::vector<Sums>();
  }
  // The measured figures behind the decision (zeros until then).
  struct Decision {
    double v_off = 0, v_on = 0, c_off = 0, c_on = 0;
  };
  const Decision &decision() const { return decision_; }

  template <class Writer>
  void save(Writer &w) const {
    w.put(uint8_t(state_)), w.put(passes_), w.put(work_[0]), w.put(work_[1]), w.put(decision_);
    w.put_array(std::span<const Sums>(sums_));
  }
  template <class Reader>
  bool restore(Reader &r) {
    uint8_t state = 0;
    LightPathTrial t = *this;
    std::vector<Sums> sums;
    if (!(r.get(state) && state <= 2 && r.get(t.passes_) && r.get(t.work_[0]) && r.get(t.work_[1]) &&
          r.get(t.decision_)))
      return false;
    t.state_ = State(state);
    if (!r.get_array(sums, t.state_ == State::Trial ? sums_.size() : 0)) return false;
    t.sums_ = std::move(sums);
    *this = std::move(t);
    return true;
  }

 private:
  // No padding bytes, so that a saved state is the same bytes every time. Index 0: without light
  // paths, 1: with them.
  struct Sums {
    float pending[2] = {0, 0};  // splatted light awaiting this pass's sample
    float n = 0, sum[2] = {0, 0}, sum2[2] = {0, 0};
  };
  // Mean over the sampled pixels of an arm's per-pass variance, weighted by 1 / (mean^2 + offset) with
  // the pixel's mean with light paths.
  double variance(int arm) const {
    double v = 0;
    uint64_t pixels = 0;
    for (const Sums &s : sums_) {
      if (!(s.n > 1)) continue;
      const double n = s.n, mean = s.sum[arm] / n, m = s.sum[1] / n;
      v += std::max(0.0, (s.sum2[arm] - mean * s.sum[arm]) / (n - 1)) / (m * m + kRelativeOffset);
      ++pixels;
    }
    return pixels > 0 ? v / double(pixels) : 0.0;
  }

  State state_ = State::Off;
  std::vector<Sums> sums_;
  uint32_t passes_ = 0;      // passes measured
  double work_[2] = {0, 0};  // their summed work per camera path, without and with light paths
  Decision decision_;
};

}  // namespace nimbus::caustics
