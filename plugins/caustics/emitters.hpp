// What the caustics solver knows about each light: its kind (from the info flags), LightMix group, and
// the photon-emission densities the MIS weights need on the camera side (P_sel, P_pos, P_dir), which
// must equal what the host's sample_emission produces for the same point and direction:
//   area: uniform by area (P_pos = 1 / area, learnt from one sample_emission call per light) and
//         cosine-weighted directions (halved for two-sided emitters);
//   point: uniform sphere; spot: uniform cone of half angle acos(cos_theta_e) around the axis;
//   sun: an emission disk (P_pos = 1 / (pi R_e^2)) and a uniform cone (or a delta direction). The disk
//   starts as the host's (the scene's bounding sphere) and shrinks to the bounding sphere of the sharp
//   surfaces photons met in the probe pass (spec 6.2): the solver then places sun photons on its own disk,
//   and a receiver whose line towards the sun misses that disk has no merge technique (P_pos = 0).
// Environment lights do not emit photons (v1: uniform and dim skies are PT's job, spec 6.2; map pruning
// comes with light-selection adaptation), so their P_sel is 0 and no merge technique exists for them.
#pragma once

#include <nimbus/lights.h>

#include <vector>

#include "core/alias_table.hpp"
#include "core/math.hpp"
#include "core/sampling.hpp"

namespace nimbus::caustics {

enum class EmitterKind : uint8_t { Area, Point, Spot, Sun, Environment };

struct Emitter {
  EmitterKind kind = EmitterKind::Point;
  uint32_t flags = 0;
  uint32_t group = 0;
  float power = 0;
  Vec3f axis;              // spot: the cone axis; sun: the direction photons travel
  float cos_theta_e = -1;  // spot / sun cone
  float pdf_pos = 0;       // area: 1 / area (filled by the first photon pass); sun: 1 / (pi R_e^2)
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
  void build(std::vector<Emitter> emitters, const Vec3f &scene_center, float scene_radius) {
    emitters_ = std::move(emitters);
    scene_center_ = scene_center, scene_radius_ = scene_radius;
    set_disk(scene_center, scene_radius);
    std::vector<double> w(emitters_.size(), 0.0);
    for (size_t i = 0; i < emitters_.size(); ++i)
      w[i] = emitters_[i].kind == EmitterKind::Environment ? 0.0 : double(emitters_[i].power);
    table_ = AliasTable(w);
  }

  // The emission disk of infinite lights: perpendicular to the light's direction, centred on the
  // projection of `center`, radius `radius`.
  void set_disk(const Vec3f &center, float radius) {
    disk_center_ = center, disk_radius_ = radius;
    for (Emitter &e : emitters_)
      if (e.infinite()) e.pdf_pos = 1 / (kPi * sqr(radius));
  }
  const Vec3f &disk_center() const { return disk_center_; }
  float disk_radius() const { return disk_radius_; }
  // A photon origin on the disk for an infinite light sending light along `w`, from the same two
  // numbers as the host's disk (concentric map), outside the scene's bounding sphere.
  Vec3f disk_origin(const Vec3f &w, float u0, float u1) const {
    const Frame f = Frame::from_normal(-w);
    const Vec2f d = sample_uniform_disk_concentric(u0, u1);
    const float back = scene_radius_ + length(disk_center_ - scene_center_) + disk_radius_;
    return disk_center_ - w * back + (f.s * d.x + f.t * d.y) * disk_radius_;
  }
  // Whether the line through p along w meets the disk.
  bool on_disk(const Vec3f &p, const Vec3f &w) const {
    const Vec3f d = p - disk_center_;
    return length_squared(d - w * dot(d, w)) <= sqr(disk_radius_);
  }
  bool emits_photons() const { return !table_.empty(); }
  size_t size() const { return emitters_.size(); }
  const Emitter &operator[](size_t i) const { return emitters_[i]; }
  Emitter &operator[](size_t i) { return emitters_[i]; }
  float selection_pmf(uint32_t light) const { return table_.pmf(light); }
  int64_t pick(float u, float *pmf) const { return table_.sample(u, pmf); }

  // lp for light `l` emitting from `z`'s surface with normal `n` (area lights) along the unit direction
  // `w` (from the light towards the receiver `p`). 0 when the light cannot emit that photon.
  float lp(uint32_t l, const Vec3f &n, const Vec3f &w, const Vec3f &p) const {
    const float sel = table_.pmf(l);
    if (!(sel > 0)) return 0;
    const Emitter &e = emitters_[l];
    switch (e.kind) {
      case EmitterKind::Area: {
        const float c = dot(n, w);
        const bool two_sided = e.flags & NIMBUS_LIGHT_TWO_SIDED;
        const float pdf_dir = two_sided ? 0.5f * std::abs(c) * kInvPi : std::max(c, 0.0f) * kInvPi;
        return sel * e.pdf_pos * pdf_dir;
      }
      case EmitterKind::Point:
        return sel * kUniformSpherePdf;
      case EmitterKind::Spot:
        return dot(w, e.axis) >= e.cos_theta_e ? sel * uniform_cone_pdf(e.cos_theta_e) : 0.0f;
      case EmitterKind::Sun:
        if (!on_disk(p, w)) return 0;
        if (e.delta_direction()) return sel * e.pdf_pos;
        return dot(w, e.axis) >= e.cos_theta_e ? sel * e.pdf_pos * uniform_cone_pdf(e.cos_theta_e) : 0.0f;
      case EmitterKind::Environment:
        return 0;
    }
    return 0;
  }

 private:
  std::vector<Emitter> emitters_;
  AliasTable table_;
  Vec3f scene_center_, disk_center_;
  float scene_radius_ = 1, disk_radius_ = 1;
};

}  // namespace nimbus::caustics
