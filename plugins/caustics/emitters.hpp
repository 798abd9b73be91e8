// What the caustics solver knows about each light: its kind (from the info flags), LightMix group, and
// the photon-emission densities the MIS weights need on the camera side (P_sel, P_pos, P_dir), which
// must equal what the photon tracer produces for the same point and direction. Where the solver emits
// as the host does, those densities are the host's own (lights service pdf_emission); where it aims
// (the cones and the sun's disk or rectangle below), they are the solver's.
//
// Emission target (spec 6.2's emission disk, extended to finite lights). Photons that miss every sharp
// surface on their first segment can only be stored after a rough-sharp-rough sequence, which path
// tracing samples anyway (NEE at the rough vertex next to the light). So after the probe pass the
// solver aims photons at the bounding sphere of the sharp surfaces the probe met ("the target"):
//   sun:   an emission disk of the target's radius (P_pos = 1 / (pi R_e^2)), or the smaller rectangle
//          covering the projection of the box around the sharp vertices (P_pos = 1 / its area), and the
//          host's uniform cone (or delta direction); a receiver whose line towards the sun misses the
//          disk or rectangle has P_pos = 0;
//   point, spot: directions uniform in the cone from the light that just covers the target (a spot keeps
//          its own cone when that is narrower);
//   area:  the host's uniform point on the emitter, then directions uniform in the cone from that point
//          covering the target (cosine-weighted, as the host, from points inside the target).
// Directions outside the cone have P_dir = 0: no merge technique exists for those paths and MIS gives
// them to path tracing, so the image stays consistent. A small glass object covers a small fraction of a
// point light's sphere of directions: uniform emission would send most photons past it, the cone sends
// them towards it.
// Before the probe's target is known the target is the scene's bounding sphere (no cone for lights
// inside it). Environment lights do not emit photons (v1: uniform and dim skies are PT's job, spec 6.2;
// map pruning comes with light-selection adaptation), so their P_sel is 0 and no merge technique exists.
#pragma once

#include <nimbus/lights.h>

#include <vector>

#include <nimbus/cpp/alias_table.hpp>
#include <nimbus/cpp/math.hpp>
#include <nimbus/cpp/sampling.hpp>

namespace nimbus::caustics {

// A cone of directions around a unit axis, uniform density. Stores 1 - cos and sin^2 of its half angle
// (at most 90 degrees) rather than cos, so that a small target seen from far away stays exact.
struct EmissionCone {
  Vec3f axis;
  float one_minus_cos = 0;  // 0: no cone (emit as the host does)
  float sin2 = 0;

  bool active() const { return one_minus_cos > 0; }
  float pdf() const { return uniform_cone_pdf_narrow(one_minus_cos); }
  bool contains(const Vec3f &w) const {
    const float c = dot(w, axis);
    return c > 0 && length_squared(cross(w, axis)) <= sin2 * length_squared(w);
  }
  Vec3f sample(float u0, float u1) const {
    return Frame::from_normal(axis).to_world(sample_uniform_cone_narrow(u0, u1, one_minus_cos));
  }
  // The cone of directions from `from` that covers the sphere (center, radius); inactive when `from` is
  // inside the sphere (every direction may reach it).
  static EmissionCone towards(const Vec3f &from, const Vec3f &center, float radius) {
    EmissionCone c;
    const Vec3f d = center - from;
    const float d2 = length_squared(d), r2 = radius * radius;
    if (!(d2 > r2) || !std::isfinite(d2)) return c;
    c.sin2 = r2 / d2;
    c.one_minus_cos = c.sin2 / (1.0f + std::sqrt(1.0f - c.sin2));  // 1 - sqrt(1 - s^2), without cancellation
    c.axis = d / std::sqrt(d2);
    return c;
  }
};

enum class EmitterKind : uint8_t { Area, Point, Spot, Sun, Environment };

struct Emitter {
  EmitterKind kind = EmitterKind::Point;
  uint32_t flags = 0;
  uint32_t group = 0;
  float power = 0;
  Vec3f axis;              // spot: the cone axis; sun: the direction photons travel
  float cos_theta_e = -1;  // spot / sun cone
  float pdf_pos = 0;       // infinite lights: 1 / (the area of the solver's emission disk or rectangle)
  Vec3f position;          // point, spot
  EmissionCone cone;       // point, spot: the emission cone towards the target (inactive: the host's)
  // sun: the emission rectangle [s0, s1] x [t0, t1] around the target's centre, in the plane
  // perpendicular to each direction w, in the basis of w whose s axis follows rect_s; unused (the
  // disk) where the disk is smaller.
  bool use_rect = false;
  Vec3f rect_s;
  float rect[4] = {0, 0, 0, 0};  // s0, s1, t0, t1
  bool delta_position() const { return flags & NIMBUS_LIGHT_DELTA_POSITION; }
  bool delta_direction() const { return flags & NIMBUS_LIGHT_DELTA_DIRECTION; }
  bool infinite() const { return flags & NIMBUS_LIGHT_INFINITE; }
  // BSDF sampling can hit it (a PT hit technique exists).
  bool hittable() const { return kind == EmitterKind::Area || (infinite() && !delta_direction()); }
};

inline Emitter make_emitter(const nimbus_light_info_t &info) {
  Emitter e;
  e.flags = info.flags;
  e.group = info.group;
  e.power = std::isfinite(info.power) && info.power > 0 ? info.power : 0.0f;
  e.axis = Vec3f::load(info.axis);
  e.cos_theta_e = info.cos_theta_e;
  e.position = (Vec3f::load(info.bounds_min) + Vec3f::load(info.bounds_max)) * 0.5f;
  const bool has_axis = !is_black(e.axis);
  if (info.flags & NIMBUS_LIGHT_AREA)
    e.kind = EmitterKind::Area;
  else if (info.flags & NIMBUS_LIGHT_INFINITE)
    e.kind = has_axis && info.cos_theta_o >= 1 ? EmitterKind::Sun : EmitterKind::Environment;
  else
    e.kind = has_axis && info.cos_theta_o >= 1 ? EmitterKind::Spot : EmitterKind::Point;
  return e;
}

// The photon-emission side of the lights: the selection table (power-proportional in v1) and the
// product lp of mis.hpp for a given emitter point and direction.
class EmitterSet {
 public:
  // `lights` (host-owned) must have pdf_emission (SDK 1.2).
  void build(std::vector<Emitter> emitters, const Vec3f &scene_center, float scene_radius,
             const nimbus_host_t *host, const nimbus_host_lights_v1_t *lights) {
    host_ = host, lights_ = lights;
    emitters_ = std::move(emitters);
    scene_center_ = scene_center, scene_radius_ = scene_radius;
    set_target(scene_center, scene_radius);
    std::vector<double> w(emitters_.size(), 0.0);
    for (size_t i = 0; i < emitters_.size(); ++i)
      w[i] = emitters_[i].kind == EmitterKind::Environment ? 0.0 : double(emitters_[i].power);
    table_ = AliasTable(w);
  }

  // The emission target (see the top of this file): infinite lights emit from a disk perpendicular to
  // their direction, centred on the projection of `center`, of radius `radius`, or from the rectangle
  // that covers the projection of the box [lo, hi] (if given and smaller); finite lights aim at the
  // sphere (center, radius).
  void set_target(const Vec3f &center, float radius, const Vec3f &lo = Vec3f(kInfinity),
                  const Vec3f &hi = Vec3f(-kInfinity)) {
    disk_center_ = center, disk_radius_ = radius;
    for (Emitter &e : emitters_) {
      if (e.infinite()) {
        e.pdf_pos = 1 / (kPi * sqr(radius));
        e.use_rect = false;
        if (e.kind == EmitterKind::Sun) fit_rect(e, lo, hi);
      }
      e.cone = {};
      if (e.kind != EmitterKind::Point && e.kind != EmitterKind::Spot) continue;
      const EmissionCone c = EmissionCone::towards(e.position, center, radius);
      if (e.kind == EmitterKind::Spot && !(c.one_minus_cos < 1 - e.cos_theta_e)) continue;
      e.cone = c;
    }
  }
  // The cone photons of light `l` leaving `z` are emitted into; inactive: the host's own directions.
  EmissionCone cone(uint32_t l, const Vec3f &z) const {
    const Emitter &e = emitters_[l];
    if (e.kind == EmitterKind::Area) return EmissionCone::towards(z, disk_center_, disk_radius_);
    return e.cone;
  }
  const Vec3f &disk_center() const { return disk_center_; }
  float disk_radius() const { return disk_radius_; }
  // A photon origin on the disk (or rectangle) of infinite light `l` sending light along `w`, from two
  // uniform numbers (the disk: the host's concentric map), outside the scene's bounding sphere.
  Vec3f emission_origin(uint32_t l, const Vec3f &w, float u0, float u1) const {
    const Emitter &e = emitters_[l];
    const float back = scene_radius_ + length(disk_center_ - scene_center_) + disk_radius_;
    if (e.use_rect) {
      const Frame f = Frame::from_normal_tangent(w, e.rect_s);
      const float a = e.rect[0] + u0 * (e.rect[1] - e.rect[0]), b = e.rect[2] + u1 * (e.rect[3] - e.rect[2]);
      return disk_center_ - w * back + f.s * a + f.t * b;
    }
    const Frame f = Frame::from_normal(-w);
    const Vec2f d = sample_uniform_disk_concentric(u0, u1);
    return disk_center_ - w * back + (f.s * d.x + f.t * d.y) * disk_radius_;
  }
  // Whether the line through p along w meets the disk (or rectangle) of infinite light `l`.
  bool on_target(uint32_t l, const Vec3f &p, const Vec3f &w) const {
    const Emitter &e = emitters_[l];
    const Vec3f d = p - disk_center_;
    if (e.use_rect) {
      const Frame f = Frame::from_normal_tangent(w, e.rect_s);
      const float a = dot(d, f.s), b = dot(d, f.t);
      return a >= e.rect[0] && a <= e.rect[1] && b >= e.rect[2] && b <= e.rect[3];
    }
    return length_squared(d - w * dot(d, w)) <= sqr(disk_radius_);
  }
  bool emits_photons() const { return !table_.empty(); }
  size_t size() const { return emitters_.size(); }
  const Emitter &operator[](size_t i) const { return emitters_[i]; }
  Emitter &operator[](size_t i) { return emitters_[i]; }
  float selection_pmf(uint32_t light) const { return table_.pmf(light); }
  int64_t pick(float u, float *pmf) const { return table_.sample(u, pmf); }

  // lp for light `l` emitting from `z` (area lights: with surface normal `n`) along the unit direction
  // `w` (from the light towards the receiver `p`). 0 when the light cannot emit that photon.
  float lp(uint32_t l, const Vec3f &z, const Vec3f &n, const Vec3f &w, const Vec3f &p) const {
    const float sel = table_.pmf(l);
    if (!(sel > 0)) return 0;
    const Emitter &e = emitters_[l];
    if (e.kind == EmitterKind::Environment || (e.infinite() && !on_target(l, p, w))) return 0;
    const EmissionCone c = e.infinite() ? EmissionCone() : cone(l, z);
    // The host's densities only where the solver's do not replace them (its cones, the sun's disk or
    // rectangle) and are not 1 by the SDK's convention for delta positions and directions: this runs at
    // every emitter hit and NEE sample of a camera path.
    float pdf_pos = 1, pdf_dir = 1;
    const bool host_pos = !e.infinite() && !e.delta_position();
    const bool host_dir = !(e.infinite() && e.delta_direction()) && !c.active();
    if (host_pos || host_dir) {
      float za[3], na[3], wa[3];
      z.store(za), n.store(na), w.store(wa);
      lights_->pdf_emission(host_, l, za, na, wa, &pdf_pos, &pdf_dir);
    }
    if (e.infinite())
      pdf_pos = e.pdf_pos;  // the solver's disk or rectangle
    else if (c.active())
      pdf_dir = c.contains(w) ? c.pdf() : 0.0f;
    return sel * pdf_pos * pdf_dir;
  }

 private:
  // The sun's rectangle: the bounds of the box's corners projected along the sun's axis, in the basis
  // whose s axis follows the box edge that projects longest (a pool's water seen from an oblique sun:
  // ~1.1x its projected area, where the disk around its sphere is ~2.3x). Directions within the sun's
  // cone tilt the plane and its basis by about its half angle: a margin of a few times that angle times
  // the box's farthest corner keeps every box point inside for all of them.
  void fit_rect(Emitter &e, const Vec3f &lo, const Vec3f &hi) const {
    if (!(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z)) return;
    const Vec3f a = normalize(e.axis), ext = hi - lo;
    Vec3f edge(1, 0, 0);
    float longest = -1;
    for (int k = 0; k < 3; ++k) {
      Vec3f u(0, 0, 0);
      u[k] = 1;
      const float len = length(u - a * dot(u, a)) * ext[k];
      if (len > longest) longest = len, edge = u;
    }
    const Frame f = Frame::from_normal_tangent(a, edge);
    float r[4] = {kInfinity, -kInfinity, kInfinity, -kInfinity}, far = 0;
    for (int c = 0; c < 8; ++c) {
      const Vec3f d = Vec3f(c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z) - disk_center_;
      const float s = dot(d, f.s), t = dot(d, f.t);
      r[0] = std::min(r[0], s), r[1] = std::max(r[1], s), r[2] = std::min(r[2], t), r[3] = std::max(r[3], t);
      far = std::max(far, length(d));
    }
    // To first order the s axis turns by the half angle, the t axis by twice it: 3x for room.
    const float sin_half = e.delta_direction() ? 0.0f : std::sqrt(std::max(0.0f, 1 - sqr(e.cos_theta_e)));
    const float margin = 3 * sin_half * far + 1e-4f * scene_radius_;
    r[0] -= margin, r[1] += margin, r[2] -= margin, r[3] += margin;
    const float area = (r[1] - r[0]) * (r[3] - r[2]);
    if (!(area > 0) || !(area < kPi * sqr(disk_radius_))) return;
    e.use_rect = true, e.rect_s = f.s, e.pdf_pos = 1 / area;
    std::copy(r, r + 4, e.rect);
  }

  std::vector<Emitter> emitters_;
  const nimbus_host_t *host_ = nullptr;
  const nimbus_host_lights_v1_t *lights_ = nullptr;
  AliasTable table_;
  Vec3f scene_center_, disk_center_;
  float scene_radius_ = 1, disk_radius_ = 1;
};

}  // namespace nimbus::caustics
