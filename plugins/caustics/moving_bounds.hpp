// Where a lookup may merge the photons of the whole shutter (spec 7.1). A camera path whose segments,
// from the lens to the lookup vertex, meet nothing that moves sees the same surfaces at every time of the
// shutter: its importance at the vertex does not depend on its time, so the pixel's mean is the path's
// importance times the vertex's light averaged over the shutter, which the photons of every time
// estimate without a time window. Such lookups take every photon (several times the window's share);
// the others keep the window. The host's moving_bounds (SDK 1.9) bound what moves over the whole
// shutter, so a segment that meets none of them is still at every time.
//
// A first lookup's segment is tested from the lens's centre against the bounds grown by the lens's
// radius, so that the splat and light-tracing techniques, which connect a first vertex to a lens point
// of their own, tell exactly as the camera path does whether its merge takes the whole shutter
// (the merge's density in MIS, merging.hpp's first_merge_densities).
#pragma once

#include <nimbus/nimbus.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include <nimbus/cpp/math.hpp>

namespace nimbus::caustics {

// More moving objects than this are tested as one box around them all: a bound still, and the test per
// segment stays cheap.
inline constexpr uint32_t kMaxMovingBoxes = 16;

class MovingBounds {
 public:
  struct Box {
    Vec3f lo, hi;
  };

  // [main-thread] From the host's scene query and camera, for a render whose photons carry times
  // (timed). Off, so that every lookup keeps the window, when photons are untimed, the camera moves,
  // or the host cannot tell what moves.
  static MovingBounds of(const nimbus_host_t *h, const nimbus_host_scene_query_v1_t *scene,
                         const nimbus_host_camera_v1_t *camera, bool timed) {
    MovingBounds m;
    if (!timed || !NIMBUS_HAS_MEMBER(scene, nimbus_host_scene_query_v1_t, moving_bounds) ||
        !NIMBUS_HAS_MEMBER(camera, nimbus_host_camera_v1_t, shutter))
      return m;
    float open = 0, close = 0;
    if (camera->shutter(h, &open, &close) & NIMBUS_MOTION_CAMERA) return m;
    std::vector<nimbus_object_bounds_t> b(scene->moving_bounds(h, nullptr, 0));
    b.resize(scene->moving_bounds(h, b.data(), uint32_t(b.size())));
    for (const nimbus_object_bounds_t &o : b) m.boxes_.push_back({Vec3f::load(o.lo), Vec3f::load(o.hi)});
    if (m.boxes_.size() > kMaxMovingBoxes) {
      Box all = m.boxes_[0];
      for (const Box &o : m.boxes_) all.lo = min(all.lo, o.lo), all.hi = max(all.hi, o.hi);
      m.boxes_.assign(1, all);
    }
    // The lens: the centre and radius of the origins of rays through the image's centre, its rim drawn
    // from the lens square's corners and edges (a pinhole gives one point).
    uint32_t width = 0, height = 0;
    camera->resolution(h, &width, &height);
    Vec3f org[9];
    for (int i = 0; i < 9; ++i) {
      const nimbus_camera_sample_t s{{0.5f * float(width), 0.5f * float(height)},
                                     {0.5f * float(i % 3), 0.5f * float(i / 3)}};
      nimbus_ray_t ray{};
      camera->generate_ray(h, &s, &ray);
      org[i] = Vec3f::load(ray.org);
    }
    m.lens_ = org[4];
    for (const Vec3f &o : org) m.lens_radius_ = std::max(m.lens_radius_, length(o - m.lens_));
    // Grown by a hair, relative to the boxes and the lens, against rounding in the tests below.
    for (Box &o : m.boxes_) {
      const float pad = 1e-4f * (length(o.hi - o.lo) + length(o.lo - m.lens_)) + 1e-12f;
      o.lo -= Vec3f(pad), o.hi += Vec3f(pad);
    }
    m.lens_radius_ *= 1.0001f;
    m.enabled_ = true;
    return m;
  }

  // Whether any lookup can take the whole shutter.
  bool enabled() const { return enabled_; }
  const std::vector<Box> &boxes() const { return boxes_; }

  // [any-thread] Whether the segment from any lens point to the first vertex x meets nothing that moves.
  bool lens_segment_still(const Vec3f &x) const {
    if (!enabled_) return false;
    for (const Box &b : boxes_)
      if (meets({b.lo - Vec3f(lens_radius_), b.hi + Vec3f(lens_radius_)}, lens_, x)) return false;
    return true;
  }
  // [any-thread] Whether the segment from a to b meets nothing that moves.
  bool segment_still(const Vec3f &a, const Vec3f &b) const {
    if (!enabled_) return false;
    for (const Box &box : boxes_)
      if (meets(box, a, b)) return false;
    return true;
  }

  // Whether the segment from a to b, ends included, meets the box (slabs; an axis the segment runs
  // parallel to keeps it only when a lies between the box's planes).
  static bool meets(const Box &box, const Vec3f &a, const Vec3f &b) {
    float t0 = 0, t1 = 1;
    for (int k = 0; k < 3; ++k) {
      const float d = b[k] - a[k];
      if (d == 0) {
        if (a[k] < box.lo[k] || a[k] > box.hi[k]) return false;
        continue;
      }
      float near = (box.lo[k] - a[k]) / d, far = (box.hi[k] - a[k]) / d;
      if (near > far) std::swap(near, far);
      t0 = std::max(t0, near), t1 = std::min(t1, far);
      if (t0 > t1) return false;
    }
    return true;
  }

 private:
  std::vector<Box> boxes_;
  Vec3f lens_{0, 0, 0};
  float lens_radius_ = 0;
  bool enabled_ = false;
};

}  // namespace nimbus::caustics
