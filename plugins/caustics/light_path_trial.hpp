// Whether light paths pay on this scene (light_paths.hpp): an equal-time comparison the render runs on
// itself. Light tracing shares its paths with path tracing, merges and splats through MIS, which weighs
// densities and not variances, so no model of how shares shift when it is added predicts its worth: in
// a closed room under a point light it renders the indirect light 4x better at equal time, on a glass
// on an open floor it adds cost and little else. The first 2 kTrialIterations camera passes with a map
// alternate with and without light paths; each pixel's light per iteration (its camera sample and the
// splats into it) gives each arm's relative variance per iteration, weighted as relMSE weighs it, and
// the arms' work per iteration their cost; light paths stay on when variance times cost is lower with
// them. Both arms are unbiased renders, so the trial's iterations all count.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "useful_pixels.hpp"

namespace nimbus::caustics {

// Passes of each arm before the decision. Fewer measure the first maps, whose merges' noise hides what
// light paths save (cornell-point: with two or three passes each, 0.73-0.88 of the variance without
// them; with eight, 0.47), and each pass without them where they pay costs the image for good (one
// leaves 6x the variance in cornell-point's side-wall caustic).
inline constexpr uint32_t kTrialIterations = 8;

class LightPathTrial {
 public:
  enum class State : uint8_t { Trial = 0, On = 1, Off = 2 };

  // [main-thread] A new render of `pixels` pixels; possible: light paths can be traced at all.
  void reset(size_t pixels, bool possible) {
    state_ = possible ? State::Trial : State::Off;
    sums_.assign(possible ? pixels : 0, Sums{});
    passes_ = 0, work_[0] = work_[1] = 0, iterations_[0] = iterations_[1] = 0;
    arm_ = false;
  }
  State state() const { return state_; }

  // [main-thread] Whether the next camera pass (one with a map) traces light paths; counts it.
  bool next_pass() {
    arm_ = state_ == State::On || (state_ == State::Trial && passes_ % 2 == 1);
    ++passes_;
    return arm_;
  }
  bool measuring() const { return state_ == State::Trial; }

  // [main-thread] Light (luminance) splatted into pixel i before this pass's camera samples.
  void add_splat(size_t i, float light) {
    if (measuring() && i < sums_.size()) sums_[i].pending += light;
  }
  // [render-thread] Pixel i's camera sample (each pixel belongs to one tile: no two threads meet).
  void add_sample(size_t i, float beauty) {
    if (!measuring() || i >= sums_.size()) return;
    Sums &s = sums_[i];
    const float v = beauty + s.pending;
    s.pending = 0;
    s.n[arm_] += 1, s.sum[arm_] += v, s.sum2[arm_] += v * v;
  }

  // [main-thread] The pass ended; work: its work units per camera path (camera paths, light paths and
  // the photon paths of its map's share). Decides once both arms have kTrialIterations passes.
  void pass_done(double work) {
    if (!measuring()) return;
    work_[arm_] += work, iterations_[arm_] += 1;
    if (iterations_[0] < kTrialIterations || iterations_[1] < kTrialIterations) return;
    const double v_off = variance(false), v_on = variance(true);
    const double c_off = work_[0] / iterations_[0], c_on = work_[1] / iterations_[1];
    state_ = v_on * c_on < v_off * c_off ? State::On : State::Off;
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
    w.put(uint8_t(state_)), w.put(passes_), w.put(work_[0]), w.put(work_[1]);
    w.put(iterations_[0]), w.put(iterations_[1]), w.put(decision_);
    w.put_array(std::span<const Sums>(sums_));
  }
  template <class Reader>
  bool restore(Reader &r) {
    uint8_t state = 0;
    LightPathTrial t = *this;
    std::vector<Sums> sums;
    if (!(r.get(state) && state <= 2 && r.get(t.passes_) && r.get(t.work_[0]) && r.get(t.work_[1]) &&
          r.get(t.iterations_[0]) && r.get(t.iterations_[1]) && r.get(t.decision_)))
      return false;
    t.state_ = State(state);
    if (!r.get_array(sums, t.state_ == State::Trial ? sums_.size() : 0)) return false;
    t.sums_ = std::move(sums);
    *this = std::move(t);
    return true;
  }

 private:
  // No padding bytes, so that a saved state is the same bytes every time.
  struct Sums {
    float pending = 0;                                       // splatted light awaiting this pass's sample
    float n[2] = {0, 0}, sum[2] = {0, 0}, sum2[2] = {0, 0};  // per arm: without, with light paths
  };
  // Mean over the pixels sampled in both arms of an arm's per-iteration variance, weighted by
  // 1 / (mean^2 + offset) with the pixel's mean over both arms.
  double variance(bool arm) const {
    double v = 0;
    uint64_t pixels = 0;
    for (const Sums &s : sums_) {
      if (!(s.n[0] > 1 && s.n[1] > 1)) continue;
      const double n = s.n[arm], mean = s.sum[arm] / n;
      const double var = std::max(0.0, (s.sum2[arm] - mean * s.sum[arm]) / (n - 1));
      const double m = (double(s.sum[0]) + s.sum[1]) / (double(s.n[0]) + s.n[1]);
      v += var / (m * m + kRelativeOffset);
      ++pixels;
    }
    return pixels > 0 ? v / double(pixels) : 0.0;
  }

  State state_ = State::Off;
  std::vector<Sums> sums_;
  uint64_t passes_ = 0;              // camera passes with a map so far
  double work_[2] = {0, 0};          // per arm, summed work per camera path
  uint32_t iterations_[2] = {0, 0};  // per arm, passes measured
  bool arm_ = false;                 // the current pass's
  Decision decision_;
};

}  // namespace nimbus::caustics
