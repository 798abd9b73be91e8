// The mutation size d of each photon pass (caustics-solver.md §6.3). d is fixed within a pass, so each
// pass is a plain Metropolis-Hastings chain whose moves keep T/b, and adapted between passes towards an
// acceptance of 0.234 (Hachisuka & Jensen 2011's target, the classic optimal random-walk scaling):
//   d <- clamp(d * exp(A - 0.234), 1e-4, 0.5),   A = accepted / proposals of the pass.
// A pass begun again (a resumed render rebuilding its last pass's photons, nimbus/guiding.h) runs with
// the d it had the first time and its end changes nothing, so the resumed render equals the original.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>

#include <nimbus/cpp/render_state.hpp>

namespace nimbus::guide {

class MutationSchedule {
 public:
  static constexpr double kInitial = 0.05, kMin = 1e-4, kMax = 0.5, kTargetAcceptance = 0.234;

  // The next d after a pass that ran with d and accepted `accepted` of `proposals` mutations; a pass
  // without proposals (every chain uniform-only) says nothing about d.
  static double adapted(double d, uint64_t accepted, uint64_t proposals) {
    if (proposals == 0) return d;
    const double acceptance = double(accepted) / double(proposals);
    return std::clamp(d * std::exp(acceptance - kTargetAcceptance), kMin, kMax);
  }

  // Pass `pass` (1-based) begins: its d, or nothing when the pass is 0 or earlier than the last ended
  // one (passes only go forward within a render; prepare starts a new one with reset()).
  std::optional<double> begin(uint64_t pass) {
    if (pass == 0 || pass < last_pass_) return std::nullopt;
    current_pass_ = pass;
    replaying_ = pass == last_pass_;
    current_d_ = replaying_ ? last_d_ : next_d_;
    return current_d_;
  }

  // The pass begun last ends with `accepted` of `proposals` mutations accepted. False without a pass.
  bool end(uint64_t accepted, uint64_t proposals) {
    if (current_pass_ == 0) return false;
    if (!replaying_) {
      last_pass_ = current_pass_, last_d_ = current_d_;
      next_d_ = adapted(current_d_, accepted, proposals);
    }
    current_pass_ = 0;
    return true;
  }

  void reset() { *this = MutationSchedule{}; }
  double next_d() const { return next_d_; }

  // The render state (nimbus/render_state.h): what the next pass and a replay of the last one need.
  void save(sdk::StateWriter &w) const {
    w.put(kStateVersion), w.put(last_pass_), w.put(last_d_), w.put(next_d_);
  }
  // NIMBUS_E_VERSION for another format, NIMBUS_E_INVALID_ARG for bytes this format cannot hold (a d
  // outside [kMin, kMax], a short or long state); the schedule changes only when everything was read.
  nimbus_status_t restore(sdk::StateReader &r) {
    uint32_t version = 0;
    MutationSchedule s;
    if (!r.get(version)) return NIMBUS_E_INVALID_ARG;
    if (version != kStateVersion) return NIMBUS_E_VERSION;
    if (!(r.get(s.last_pass_) && r.get(s.last_d_) && r.get(s.next_d_) && r.done()))
      return NIMBUS_E_INVALID_ARG;
    if (!valid(s.last_d_) || !valid(s.next_d_)) return NIMBUS_E_INVALID_ARG;
    *this = s;
    return NIMBUS_OK;
  }

 private:
  static constexpr uint32_t kStateVersion = 1;
  static bool valid(double d) { return d >= kMin && d <= kMax; }  // false for NaN too

  uint64_t last_pass_ = 0;     // the last pass that ended, 0 for none
  double last_d_ = kInitial;   // the d it ran with
  double next_d_ = kInitial;   // the d of the next new pass
  uint64_t current_pass_ = 0;  // the pass begun and not ended, 0 for none
  double current_d_ = kInitial;
  bool replaying_ = false;  // the current pass is the last one again
};

}  // namespace nimbus::guide
