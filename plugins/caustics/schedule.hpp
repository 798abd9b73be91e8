// When to trace photons and how many (spec sections 3.5, 5 and 9), as a small state machine the plugin
// drives from its iteration hooks: the merge radius schedule, the photon budget that minimises the
// image's error at equal time, interleaving of photon and camera passes, and back-off when photons are
// useless.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace nimbus::caustics {

inline constexpr float kRadiusPixels = 1.5f;  // initial merge radius in pixel footprints
inline constexpr float kRadiusAlpha = 0.75f;  // Knaus-Zwicker alpha: r^2 ~ j^(alpha - 1)
// Useful pixels (spec 5): a pixel is useful iff Mp > tau Tp, Mp its MIS-weighted merge light and Tp its
// beauty. No useful pixel after an iteration: back off (no photons for a while).
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
  uint64_t n_max = uint64_t(1) << 22;  // photon paths per pass (spec 5: a fixed maximum)
  // A floor low enough that a map reused over several iterations stays small: a lookup's cost grows with
  // the map's photons (kLeafWork), so a large floor pass served k times costs k times its photon paths.
  uint64_t n_min = uint64_t(1) << 10;
  uint64_t probe = uint64_t(1) << 16;  // the first pass
  uint64_t camera_paths = 1;           // camera paths per iteration (the render region's pixels)
  // The whole frame's pixels (0: camera_paths). A pass's size follows the frame, not the region: a small
  // render region still gets the large batches that guiding needs (paper 3.3), each map serving more
  // iterations, so photon paths per camera path stay at rho.
  uint64_t frame_pixels = 0;
};

// Camera passes a photon map serves at least (see pass_done).
inline constexpr uint64_t kMinIterationsPerMap = 2;

// Work units of the budget's cost model, counted rather than timed so that the photon budget, and so the
// image, does not depend on the machine's load or the thread count (same seed, same image). A ray with
// the surface interaction the host builds for it is 2 units; a photon a lookup evaluates (one host BSDF
// evaluation and the kernel) or a photon stored (copy and kd-tree build) is 1; a kd-tree leaf a lookup
// scans (the descent to it and 8 positions: cache misses, whether or not a photon lies within r) is
// kLeafWork.
inline constexpr uint64_t kRayWork = 2, kPhotonWork = 1, kLeafWork = 1;

// What the solver measured over the last iterations (spec 5's efficiency model): per camera path, the
// summed relative variance of the image carried by merges (v_merge) and by the rest (v_camera), at
// photon paths per camera path `rho`; the work per camera path, and per photon path, which includes its
// share of the lookups (their cost grows with the photons in the map, not with the camera paths).
struct EfficiencySample {
  double v_merge = 0, v_camera = 0, rho = 0;
  double camera_work = 0, photon_work = 0;
};

// Photon work per iteration is at most this multiple of the camera paths' work. The variance split
// cannot see the part of the merges' variance that only camera samples reduce (the caustic's variation
// within a pixel), so where merges carry nearly all the light the extrapolated V_m1 keeps growing with
// rho; the guard keeps a quarter of every iteration for camera paths.
inline constexpr double kMaxPhotonWorkRatio = 3;

// The photon paths per camera path that minimise error x time, t(rho) V(rho) with t = c_c + rho c_p and
// V = V_c + V_m1 / rho, V_m1 = v_merge rho (merge variance falls as 1 / photon paths): rho* =
// sqrt(V_m1 c_c / (V_c c_p)), the optimal split of a two-stage estimator, within the guard above. 0 when
// unmeasured.
inline double optimal_photon_ratio(const EfficiencySample &e) {
  if (!(e.v_merge > 0) || !(e.rho > 0) || !(e.camera_work > 0) || !(e.photon_work > 0)) return 0;
  const double guard = kMaxPhotonWorkRatio * e.camera_work / e.photon_work;
  if (!(e.v_camera > 0)) return guard;
  return std::min(guard, std::sqrt(e.v_merge * e.rho * e.camera_work / (e.v_camera * e.photon_work)));
}

class PhotonSchedule {
 public:
  PhotonSchedule() = default;
  explicit PhotonSchedule(const ScheduleConfig &c) : cfg_(c) {}

  // Photon paths to trace before the camera pass of `iteration` (0: none, keep the current map).
  uint64_t plan(uint64_t iteration) const {
    if (iteration < next_pass_) return 0;
    if (passes_ == 0) return cfg_.probe;
    if (idle_ > 0) return cfg_.n_min;
    const double pixels = double(std::max(cfg_.frame_pixels, cfg_.camera_paths));
    const double n = std::round(rho_ * double(kMinIterationsPerMap) * pixels);
    return uint64_t(std::clamp(n, double(cfg_.n_min), double(cfg_.n_max)));
  }

  // A photon pass of `paths` paths stored `stored` photons before the camera pass of `iteration`.
  void pass_done(uint64_t iteration, uint64_t paths, uint64_t stored) {
    ++passes_;
    if (stored == 0) {
      active_ = false;
      back_off(iteration);
      return;
    }
    active_ = true;
    // A pass serves about paths / (rho N_cam) camera passes, so that photon paths per camera path stay
    // near rho (the probe and the N_min floor serve more); at least two, so that the variance split
    // (useful_pixels.hpp) sees samples under one map.
    const double per_iteration = std::max(1.0, rho_ * double(cfg_.camera_paths));
    serves_ = std::max<uint64_t>(kMinIterationsPerMap, uint64_t(std::llround(double(paths) / per_iteration)));
    map_rho_ = double(paths) / (double(serves_) * double(cfg_.camera_paths));
    next_pass_ = iteration + serves_;
  }

  // After the camera pass of `iteration` (meaningful when a map was active): the share of useful pixels
  // decides whether to back off; the measured efficiency sizes the next passes (rho smoothed in log
  // space over passes: the variance estimates are noisy).
  void iteration_done(uint64_t iteration, double useful, const EfficiencySample &e) {
    if (!active_) return;
    if (const double r = optimal_photon_ratio(e); r > 0)
      rho_ = measured_ ? std::exp(0.5 * (std::log(rho_) + std::log(r))) : r, measured_ = true;
    if (useful > 0) {
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
  double photon_ratio() const { return rho_; }          // rho the budget aims at
  double map_photon_ratio() const { return map_rho_; }  // photon paths per camera path of the current map
  uint64_t iterations_per_map() const { return serves_; }
  const ScheduleConfig &config() const { return cfg_; }

  // The whole state, for a resumed render (sdk::StateWriter and sdk::StateReader); restore changes
  // nothing unless it reads all of it.
  template <class Writer>
  void save(Writer &w) const {
    w.put(cfg_), w.put(next_pass_), w.put(serves_), w.put(passes_), w.put(idle_), w.put(rho_);
    w.put(map_rho_), w.put(uint8_t(measured_)), w.put(uint8_t(active_));
  }
  template <class Reader>
  bool restore(Reader &r) {
    PhotonSchedule s;
    uint8_t measured = 0, active = 0;
    if (!(r.get(s.cfg_) && r.get(s.next_pass_) && r.get(s.serves_) && r.get(s.passes_) && r.get(s.idle_) &&
          r.get(s.rho_) && r.get(s.map_rho_) && r.get(measured) && r.get(active)))
      return false;
    s.measured_ = measured != 0, s.active_ = active != 0;
    *this = s;
    return true;
  }

 private:
  // The next pass comes after 2^b iterations without photons, starting at `first_idle`.
  void back_off(uint64_t first_idle) {
    idle_ = std::min(idle_ + 1, kMaxIdleLevel);
    next_pass_ = first_idle + (uint64_t(1) << idle_);
  }

  ScheduleConfig cfg_;
  uint64_t next_pass_ = 1, serves_ = 1;
  uint32_t passes_ = 0, idle_ = 0;
  // Until measured, half a photon path per camera path (the equal-time optimum on the shipped caustic
  // scenes under the previous, fixed rule).
  double rho_ = 0.5, map_rho_ = 0;
  bool measured_ = false;
  bool active_ = false;
};

}  // namespace nimbus::caustics
