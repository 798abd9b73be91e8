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
// 10 % of the light, not the spec's 1 % (the LPM constant), by the spec's own rule for tau ("revisit if
// overhead above target"): measured side by side on 2 cores (docs/performance.md §4), 0.1 against 0.01
// gave u 0.25 -> 0.11 on sphere-point, 0.26 -> 0.13 on sphere-area, 0.46 -> 0.40 on the ring, time per
// iteration 0.92 / 0.91 / 0.98 of before, at 1.11 / 1.12 / 1.17x the variance at equal time. Backing off
// (no photons for a while) still needs no pixel over 1 %: a caustic that is faint everywhere keeps its
// photons, at N_min per pass.
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
  // (one host BSDF call each) and one photon path costs about 0.7 camera paths, so photon work per
  // iteration scales with this ratio. Measured on 2 cores at 640x360 (docs/performance.md): ratio 2 cost
  // +122 % per iteration on the pool scene (u = 0.6) and +70 % on the ring; the uncapped 2^22 more than
  // doubled render time. With 0.5 the photon work stays near a third of the camera work even when every
  // pixel is useful; noise at equal time is what matters, and more iterations per second make up for
  // smaller maps. Variance x seconds at 32 iterations (bench/efficiency.py, docs/performance.md §4), ratio
  // 0.25 / 0.5 / 1: pool 0.44 / 0.34 / 0.30, ring 0.043 / 0.026 / 0.017, sphere-point 0.051 / 0.051 /
  // 0.056, sphere-area 0.045 / 0.043 / 0.050, glasses 0.22 / 0.20 / 0.26: 0.5 is near the optimum on
  // all five. Metropolis guiding (next issue) wants large batches: revisit the cap with it.
  // The probe (2^16 paths) is not capped, so small images still interleave several camera passes per
  // photon pass.
  double photon_paths_per_camera_path = 0.5;
  uint64_t probe = uint64_t(1) << 16;  // the first pass
  // N_min never below this (the spec's N_min = 2^22 / 64 = 2^16 is kept for the probe). Small caustics
  // (a useful-pixel ratio near 0) get N_min paths per pass, so the floor sets their photon density. The
  // spec's 2^16 assumes photons emitted over each light's whole range, most of them missing every
  // caustic-forming surface (uniform emission stored ~1 photon per 60 paths on sphere-point). Photons are
  // now aimed at the sharp surfaces (emitters.hpp) and 2^14 paths store 4-10x more photons per pass than
  // 2^16 did. Measured at 640x360 on 2 cores (docs/performance.md), 2^14 against 2^16: overhead per
  // iteration over nimbus.pt 33 / 42 / 38 / 26 % against 97 / 81 / 57 / 65 % on sphere-point /
  // sphere-area / ring / glasses; relMSE at equal time the same on sphere-point and glasses, ~15 % lower
  // on sphere-area (more iterations), 1.5x higher on the ring (still ~1000x below nimbus.pt's).
  uint64_t min_floor = 16384;
  // Cap on the photons a pass stores, relative to the camera paths of one iteration (0: none), applied
  // through the photons stored per path in the previous pass. Lookups and the map build scale with the
  // stored photons, not with the paths: the pool stores ~1.06 photons per path, the other scenes
  // 0.3-0.85, and its lookups alone cost ~28 % of nimbus.pt's time at 0.5 paths per camera path
  // (docs/performance.md §4). 1/6 bound on the pool only (~37,000 stored photons per pass at 640x360
  // instead of ~74,000): measured side by side on 2 cores, its time per iteration fell by 16 % (overhead
  // 78 % -> 42 %, the others unchanged) at 1.4-1.6x its variance at equal time. That left the pool at
  // 42-48 %, above the spec's 40 % target, so by the spec's rule for N_max ("revisit if overhead above
  // target") the cap is now 1/8 (~29,000 photons): time per iteration 0.95 of 1/6's, overhead 47 % ->
  // 39 %, at 1.24x the variance at equal time (1/10: 0.92, 35 %, 1.49x). The other scenes store under
  // 1/8 per camera path. 0 removes the cap (best equal-time error).
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
    if (dormant_ || iteration < next_pass_) return 0;
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

  // No photon path can ever be stored (no sharp surface met by photons or camera paths): stop planning
  // until the camera reports one.
  void set_dormant(bool d) { dormant_ = d; }
  bool dormant() const { return dormant_; }

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
  bool active_ = false, dormant_ = false;
};

}  // namespace nimbus::caustics
