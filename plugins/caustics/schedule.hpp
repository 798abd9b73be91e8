// When to trace photons and how many (spec sections 3.5, 5 and 9), as a small state machine the plugin
// drives from its iteration hooks: the merge radius schedule, the photon budget from the useful-pixel
// ratio, interleaving of photon and camera passes, and back-off when photons are useless.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace nimbus::caustics {

inline constexpr float kRadiusPixels = 1.5f;  // initial merge radius in pixel footprints
inline constexpr float kRadiusAlpha = 0.75f;  // Knaus-Zwicker alpha: r^2 ~ j^(alpha - 1)
// Useful pixels (spec 5): a pixel is useful iff Mp > tau Tp, Mp its MIS-weighted merge light and Tp its
// beauty. Two thresholds, one per decision. The photon budget counts the pixels where merges bring over
// 10 % of the light, not the spec's 1 % (the LPM constant): by the spec's own rule for tau ("revisit if
// overhead above target") it trades some equal-time variance for a lower cost per iteration
// (docs/performance.md §4). Backing off (no photons for a while) still needs no pixel over 1 %: a caustic
// that is faint everywhere keeps its photons, at N_min per pass.
inline constexpr double kBudgetThreshold = 0.1;
inline constexpr double kIdleThreshold = 0.01;
inline constexpr uint32_t kMaxIdleLevel = 8;

// Merge radius per unit path length at photon pass j (1-based): kRadiusPixels theta_pix j^((alpha-1)/2),
// theta_pix the angular width of one pixel at the image centre. One pow per pass, not per camera path.
inline float radius_per_length(float theta_pix, uint32_t j) {
  return kRadiusPixels * theta_pix * std::pow(float(std::max(j, 1u)), (kRadiusAlpha - 1) / 2);
}

// Merge radius for a camera path whose first rough vertex lies at path length `ell` from the lens,
// clamped below at 1e-6 of the scene radius.
inline float merge_radius(float per_length, float ell, float scene_radius) {
  return std::max(per_length * ell, 1e-6f * scene_radius);
}
inline float merge_radius(float theta_pix, float ell, uint32_t j, float scene_radius) {
  return merge_radius(radius_per_length(theta_pix, j), ell, scene_radius);
}

struct ScheduleConfig {
  uint64_t n_max = uint64_t(1) << 22;  // photon paths per pass at u = 1 (spec 5)
  // Cap on photon paths per pass relative to the camera paths of one iteration (0: none):
  // N_max = min(2^22, ratio N_cam). Every camera pass evaluates each stored photon in ~pi 1.5^2 lookups
  // (one host BSDF call each), so photon work per iteration scales with this ratio. Noise at equal time
  // is what matters: more iterations per second make up for smaller maps. 0.5 sits near the equal-time
  // optimum on the caustic scenes: 0.25 does worse on the ring, 1.0 on sphere-point, sphere-area and
  // glasses (docs/performance.md §6). Metropolis guiding (next issue) wants large batches: revisit the
  // cap with it. The probe (2^16 paths) is not capped, so small images still interleave several camera
  // passes per photon pass.
  double photon_paths_per_camera_path = 0.5;
  uint64_t probe = uint64_t(1) << 16;  // the first pass
  // N_min never below this (the spec's N_min = 2^22 / 64 = 2^16 is kept for the probe). Small caustics
  // (a useful-pixel ratio near 0) get N_min paths per pass, so the floor sets their photon density. The
  // spec's 2^16 assumes photons emitted over each light's whole range, most of them missing every
  // caustic-forming surface. Aimed at the sharp surfaces (emitters.hpp), 2^14 paths store more photons
  // than 2^16 unaimed ones, and 2^16 would multiply the overhead without lowering the equal-time error
  // of small caustics (docs/performance.md §6).
  uint64_t min_floor = 16384;
  // Cap on the photons a pass stores, relative to the camera paths of one iteration (0: none), applied
  // through the photons stored per path in the previous pass. Lookups and the map build scale with the
  // stored photons, not with the paths: where nearly every photon path stores a photon (the pool) the
  // overhead would exceed the spec's 40 % target, so by the spec's rule for N_max ("revisit if overhead
  // above target") a pass stores at most 1/8 photon per camera path, at some cost in equal-time variance
  // (docs/performance.md §4; the tighter 1/10 in §6). Scenes that store less are not affected. 0 removes
  // the cap (best equal-time error).
  double stored_photons_per_camera_path = 1.0 / 8;
  uint64_t camera_paths = 1;  // camera paths per iteration (the render region's pixels)

  uint64_t effective_max() const {
    if (!(photon_paths_per_camera_path > 0)) return n_max;
    const double cap = std::round(photon_paths_per_camera_path * double(camera_paths));
    return std::min(n_max, std::max<uint64_t>(1, uint64_t(cap)));
  }
  uint64_t effective_min() const {
    return std::min(effective_max(), std::max(min_floor, effective_max() / 64));
  }
};

// The fraction of the render region's pixels that are useful, at each of the two thresholds.
struct UsefulRatio {
  double budget = 0;  // Mp > kBudgetThreshold Tp
  double idle = 0;    // Mp > kIdleThreshold Tp
};

class PhotonSchedule {
 public:
  PhotonSchedule() = default;
  explicit PhotonSchedule(const ScheduleConfig &c) : cfg_(c) {}

  // Photon paths to trace before the camera pass of `iteration` (0: none, keep the current map).
  uint64_t plan(uint64_t iteration) const {
    if (iteration < next_pass_) return 0;
    if (passes_ == 0) return cfg_.probe;
    const uint64_t lo = cfg_.effective_min(), hi = cfg_.effective_max();
    if (idle_ > 0) return lo;
    const double n = std::clamp(std::round(u_ * double(hi)), double(lo), double(hi));
    if (!(cfg_.stored_photons_per_camera_path > 0) || !(yield_ > 0)) return uint64_t(n);
    const double stored_cap = cfg_.stored_photons_per_camera_path * double(cfg_.camera_paths) / yield_;
    return uint64_t(std::min(n, std::max(double(lo), std::round(stored_cap))));
  }

  // A photon pass of `paths` paths stored `stored` photons before the camera pass of `iteration`.
  void pass_done(uint64_t iteration, uint64_t paths, uint64_t stored) {
    ++passes_;
    if (paths > 0 && stored > 0) yield_ = double(stored) / double(paths);
    if (stored == 0) {
      active_ = false;
      back_off(iteration);
      return;
    }
    active_ = true;
    // Large passes serve several camera passes (photon : camera paths ~ 1 over time); small ones are
    // redone every iteration.
    const uint64_t k =
        paths >= cfg_.camera_paths
            ? std::max<uint64_t>(1, uint64_t(std::llround(double(paths) / double(cfg_.camera_paths))))
            : 1;
    next_pass_ = iteration + k;
  }

  // After the camera pass of `iteration` (meaningful when a map was active): the useful-pixel ratio at
  // kBudgetThreshold sizes the next passes, the one at kIdleThreshold decides whether to back off.
  void iteration_done(uint64_t iteration, UsefulRatio u) {
    if (!active_) return;
    u_ = u.budget;
    if (u.idle > 0) {
      idle_ = 0;
      return;
    }
    active_ = false;  // photons stored but useless: plain path tracing while backing off
    back_off(iteration + 1);
  }

  // Camera paths per iteration (the render region's pixels), learnt after the first camera pass.
  void set_camera_paths(uint64_t n) { cfg_.camera_paths = std::max<uint64_t>(1, n); }

  bool map_active() const { return active_; }
  uint32_t passes() const { return passes_; }  // j of the current map
  uint32_t idle_level() const { return idle_; }
  uint64_t next_pass() const { return next_pass_; }
  double useful_ratio() const { return u_; }
  const ScheduleConfig &config() const { return cfg_; }

 private:
  // The next pass comes after 2^b iterations without photons, starting at `first_idle`.
  void back_off(uint64_t first_idle) {
    idle_ = std::min(idle_ + 1, kMaxIdleLevel);
    next_pass_ = first_idle + (uint64_t(1) << idle_);
  }

  ScheduleConfig cfg_;
  uint64_t next_pass_ = 1;
  uint32_t passes_ = 0, idle_ = 0;
  double u_ = 0;
  double yield_ = 0;  // photons stored per photon path in the last pass that stored any
  bool active_ = false;
};

}  // namespace nimbus::caustics
