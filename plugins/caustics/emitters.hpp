// What the caustics solver knows about each light: its kind (from the info flags), LightMix group, and
// how it emits photons, with the densities the MIS weights need on the camera side (P_sel, P_pos, P_dir),
// which equal what the photon tracer produces for the same point and direction.
//
// Projection maps (solver spec 6.2). Photons are aimed at the sharp geometry the host reports
// (sharp_targets.hpp) from the first pass on, so no caustic-forming object is ever left without photons:
//   point, spot, area: a mixture of the light's own emission (the host's sample_emission; a defensive
//          share of at least kOwnShare) and cones of uniform directions towards each target sphere,
//          weighted by the solid angle each target covers as seen from the light (a spot drops targets
//          outside its cone; an area light aims from each emission point, with weights fixed per light).
//          Its photons carry the power it sends towards the targets, which light selection weighs;
//   sun:   origins on a disk perpendicular to the direction, around the sphere of all targets
//          (P_pos = 1 / (pi R_e^2)), or on the smaller rectangle covering the projection of their box,
//          mixed with kOwnShare of origins on the scene's disk; the host's cone of directions.
// The density of a direction (or, for the sun, of an origin) is the mixture's: the same function on
// both sides, so MIS weights remain a partition of unity. A photon whose first vertex is rough is not
// traced on (photon_tracer.cpp), so the defensive share costs one ray per photon.
//   environment: directions from environment_emission.hpp (the bright parts of the map only; a uniform
//          map emits nothing, so its P_sel is 0 and no merge technique exists for it), origins as the
//          sun's on the targets' disk.
// With photon_emission: adaptive-map, each cone and each targets' disk or rectangle also has a learnt density
// over its two numbers (emission_map.hpp); both sides read it through the same inversions.
#pragma once

#include <nimbus/lights.h>

#include <algorithm>
#include <memory>
#include <vector>

#include <nimbus/cpp/alias_table.hpp>
#include <nimbus/cpp/math.hpp>
#include <nimbus/cpp/sampling.hpp>

#include "emission_cone.hpp"
#include "emission_map.hpp"
#include "emitter.hpp"
#include "environment_emission.hpp"
#include "sharp_targets.hpp"

namespace nimbus::caustics {

// The photon-emission side of the lights: the selection table, the projection maps, and the product lp
// of mis.hpp for a given emitter point and direction.
class EmitterSet {
 public:
  // `lights` (host-owned) must have pdf_emission (SDK 1.2). Without targets every light emits as the
  // host does (finite) or from the scene's disk (the sun).
  void build(std::vector<Emitter> emitters, const Vec3f &scene_center, float scene_radius,
             const nimbus_host_t *host, const nimbus_host_lights_v1_t *lights, SharpTargets targets) {
    host_ = host, lights_ = lights;
    emitters_ = std::move(emitters);
    targets_ = std::move(targets);
    scene_center_ = scene_center, scene_radius_ = scene_radius;
    std::vector<double> w(emitters_.size(), 0.0);
    environments_.clear();
    environments_.resize(emitters_.size());
    slots_ = 0;
    for (size_t i = 0; i < emitters_.size(); ++i) {
      Emitter &e = emitters_[i];
      if (e.kind == EmitterKind::Environment) {
        auto env = build_environment(uint32_t(i));
        if (!env->emits()) continue;
        e.power *= float(env->emitted_share());  // the flux of the part that emits photons
        environments_[i] = std::move(env);
      }
      if (e.infinite())
        aim_sun(e);
      else
        aim_finite(e);
      // A finite light's photons bring caustics only by the power it sends towards sharp geometry (a
      // spot turned away from every target sends none: path tracing samples its bounces). An infinite
      // light whose disk is the scene's, though targets exist, keeps the defensive share.
      const bool scene_disk = e.infinite() && !(e.own < 1) && !targets_.empty();
      w[i] = double(e.power) * (!e.infinite() ? double(e.toward) : scene_disk ? double(kOwnShare) : 1.0);
      e.first_slot = slots_;
      slots_ += e.infinite() ? (e.own < 1 ? 1 : 0) : uint32_t(e.aims.size());
    }
    rule_ = std::move(w);
    table_ = AliasTable(rule_);
  }

  // The flux each light's photons carry (light selection reports it to the sampler,
  // emission_selection.hpp): the power a finite light emits towards the targets; an infinite light's
  // through the targets' disk, or the defensive share of it when the disk is the scene's.
  const std::vector<double> &photon_powers() const { return rule_; }
  // The selection probabilities of the next photon map (both sides read them until the one after).
  void set_selection(const std::vector<double> &p) { table_ = AliasTable(p); }
  // [main-thread] A new render's emission map, learning (adaptive) or uniform (emission_map.hpp).
  void reset_emission_map(bool adaptive) { map_.configure(slots_, adaptive); }
  EmissionMap &emission_map() { return map_; }

  bool emits_photons() const { return !table_.empty(); }
  size_t size() const { return emitters_.size(); }
  const Emitter &operator[](size_t i) const { return emitters_[i]; }
  const SharpTargets &targets() const { return targets_; }
  float selection_pmf(uint32_t light) const { return table_.pmf(light); }
  int64_t pick(float u, float *pmf) const { return table_.sample(u, pmf); }

  // Finite light `l` emitting from `z`: the direction of the component that `u_mix` picks, from (u0, u1)
  // through the emission map for a cone, or `own` (the host's sampled direction) for the light's own
  // emission and for a cone whose target contains z. *cell: the emission map's cell (path_use.hpp).
  Vec3f sample_direction(uint32_t l, const Vec3f &z, float u_mix, float u0, float u1, const Vec3f &own,
                         uint32_t *cell = nullptr) const {
    const Emitter &e = emitters_[l];
    float c = e.own;
    if (u_mix < c) return own;
    for (size_t i = 0; i < e.aims.size(); ++i) {
      const Aim &a = e.aims[i];
      c += a.share;
      if (u_mix < c || i + 1 == e.aims.size()) {
        const EmissionCone cone = cone_of(e, a, z);
        if (!cone.active()) return own;
        const uint32_t code = map_.warp(e.first_slot + uint32_t(i), u0, u1);
        if (cell) *cell = code;
        return cone.sample(u0, u1);
      }
    }
    return own;
  }
  // The direction density of finite light `l`'s mixture at w from z (area lights: normal n), asking the
  // host for its own density there: what the photon tracer samples with.
  float finite_pdf_dir(uint32_t l, const Vec3f &z, const Vec3f &n, const Vec3f &w, float time = 0) const {
    float pdf_pos = 0, own_pdf = 0;
    own_pdfs(l, z, n, w, time, pdf_pos, own_pdf);
    return pdf_dir(l, z, w, own_pdf);
  }
  // The direction density of that mixture at w, given the host's own density there.
  float pdf_dir(uint32_t l, const Vec3f &z, const Vec3f &w, float own_pdf) const {
    const Emitter &e = emitters_[l];
    float p = e.own * own_pdf;
    for (size_t i = 0; i < e.aims.size(); ++i) {
      const Aim &a = e.aims[i];
      const EmissionCone cone = cone_of(e, a, z);
      if (!cone.active()) {
        p += a.share * own_pdf;
      } else if (cone.contains(w)) {
        const uint32_t slot = e.first_slot + uint32_t(i);
        float map = 1;
        if (map_.learnt(slot)) {
          const Vec2f u = cone.invert(w);
          map = map_.pdf(slot, u.x, u.y);
        }
        p += a.share * cone.pdf() * map;
      }
    }
    return p;
  }

  // A photon origin of the sun `l` sending light along `w`: on the targets' disk or rectangle (through
  // the emission map), or (with probability own) on the scene's disk, from two uniform numbers (disks:
  // the host's concentric map), outside the scene's bounding sphere. *cell: the emission map's cell.
  Vec3f emission_origin(uint32_t l, const Vec3f &w, float u_mix, float u0, float u1,
                        uint32_t *cell = nullptr) const {
    const Emitter &e = emitters_[l];
    const bool scene_disk = u_mix < e.own;
    if (!scene_disk) {
      const uint32_t code = map_.warp(e.first_slot, u0, u1);
      if (cell) *cell = code;
    }
    const Vec3f &center = scene_disk ? scene_center_ : targets_.all.sphere.center;
    const float back = scene_radius_ + length(center - scene_center_) + disk_radius();
    if (!scene_disk && e.use_rect) {
      const Frame f = Frame::from_normal_tangent(w, e.rect_s);
      const float a = e.rect[0] + u0 * (e.rect[1] - e.rect[0]), b = e.rect[2] + u1 * (e.rect[3] - e.rect[2]);
      return center - w * back + f.s * a + f.t * b;
    }
    const Frame f = Frame::from_normal(-w);
    const Vec2f d = sample_uniform_disk_concentric(u0, u1);
    return center - w * back + (f.s * d.x + f.t * d.y) * (scene_disk ? scene_radius_ : disk_radius());
  }
  // The environment light `l`'s photon direction (the photon travels along -dir) from three numbers.
  EnvironmentEmission::Sample environment_sample(uint32_t l, float u0, float u1, float u2) const {
    return environments_[l] ? environments_[l]->sample(u0, u1, u2) : EnvironmentEmission::Sample{};
  }

  // The density of origins of the sun `l` for the line through p along w (area measure).
  float sun_pdf_pos(uint32_t l, const Vec3f &p, const Vec3f &w) const {
    const Emitter &e = emitters_[l];
    const float scene = e.own / (kPi * sqr(scene_radius_));
    Vec2f u;
    if (!(e.own < 1) || !target_coords(e, p, w, u)) return scene;
    const float map = map_.learnt(e.first_slot) ? map_.pdf(e.first_slot, u.x, u.y) : 1.0f;
    return scene + (1 - e.own) * e.pdf_pos * map;
  }

  // lp for light `l` emitting from `z` (area lights: with surface normal `n`) along the unit direction
  // `w` (from the light towards the receiver `p`). 0 when the light cannot emit that photon.
  // time: the path's scene time, read for moving lights only.
  float lp(uint32_t l, const Vec3f &z, const Vec3f &n, const Vec3f &w, const Vec3f &p, float time = 0) const {
    const float sel = table_.pmf(l);
    if (!(sel > 0)) return 0;
    const Emitter &e = emitters_[l];
    if (e.kind == EmitterKind::Environment)
      return environments_[l] ? sel * sun_pdf_pos(l, p, w) * environments_[l]->pdf(-w) : 0.0f;
    if (e.infinite()) {
      float pdf_pos = 1, pdf_dir = 1;  // a delta direction: the SDK's convention
      if (!e.delta_direction()) own_pdfs(l, z, n, w, 0, pdf_pos, pdf_dir);
      return sel * sun_pdf_pos(l, p, w) * pdf_dir;
    }
    float pdf_pos = 1, own_pdf = 0;
    own_pdfs(l, z, n, w, time, pdf_pos, own_pdf);
    if (e.delta_position()) pdf_pos = 1;
    return sel * pdf_pos * pdf_dir(l, z, w, own_pdf);
  }

  // The host's own densities of light l; a moving light's where it is at `time`.
  void own_pdfs(uint32_t l, const Vec3f &z, const Vec3f &n, const Vec3f &w, float time, float &pdf_pos,
                float &pdf_dir) const {
    float za[3], na[3], wa[3];
    z.store(za), n.store(na), w.store(wa);
    if (emitters_[l].moves() && NIMBUS_HAS_MEMBER(lights_, nimbus_host_lights_v1_t, pdf_emission_at))
      lights_->pdf_emission_at(host_, l, za, na, wa, time, &pdf_pos, &pdf_dir);
    else
      lights_->pdf_emission(host_, l, za, na, wa, &pdf_pos, &pdf_dir);
  }
  // The emission density of environment light `l`, from the host's own emission samples of it.
  std::unique_ptr<EnvironmentEmission> build_environment(uint32_t l) const {
    auto env = std::make_unique<EnvironmentEmission>();
    env->build([&](float u0, float u1) {
      const float ue[4] = {0.5f, 0.5f, u0, u1};  // the direction is the second pair
      nimbus_light_emission_t es;
      lights_->sample_emission(host_, l, ue, &es);
      return EnvironmentEmission::LightDirection{-Vec3f::load(es.dir), luminance(Rgb::load(es.Le)),
                                                 es.pdf_dir};
    });
    return env;
  }

 private:
  // An aim's cone from emission point z: fixed for a resting point or spot light, from z itself for area
  // lights and for lights that move.
  EmissionCone cone_of(const Emitter &e, const Aim &a, const Vec3f &z) const {
    if (e.kind != EmitterKind::Area && !e.moves()) return a.cone;
    const Sphere &s = targets_.clusters[a.target].sphere;
    return EmissionCone::towards(z, s.center, s.radius);
  }
  float disk_radius() const { return targets_.all.sphere.radius; }
  // Whether the line through p along w crosses the targets' rectangle or disk; u: the numbers
  // emission_origin maps there (the emission map's coordinates, computed for a learnt map only).
  bool target_coords(const Emitter &e, const Vec3f &p, const Vec3f &w, Vec2f &u) const {
    const Vec3f d = p - targets_.all.sphere.center;
    if (e.use_rect) {
      const Frame f = Frame::from_normal_tangent(w, e.rect_s);
      const float a = dot(d, f.s), b = dot(d, f.t);
      if (!(a >= e.rect[0] && a <= e.rect[1] && b >= e.rect[2] && b <= e.rect[3])) return false;
      u = Vec2f{(a - e.rect[0]) / (e.rect[1] - e.rect[0]), (b - e.rect[2]) / (e.rect[3] - e.rect[2])};
      return true;
    }
    if (!(length_squared(d - w * dot(d, w)) <= sqr(disk_radius()))) return false;
    if (map_.learnt(e.first_slot)) {
      const Frame f = Frame::from_normal(-w);
      u = invert_uniform_disk_concentric(Vec2f{dot(d, f.s) / disk_radius(), dot(d, f.t) / disk_radius()});
    }
    return true;
  }

  // The projection map of a point, spot or area light: cones from its position towards each target it
  // can reach, weighted by solid angle; a target around the light counts as the whole sphere of
  // directions and adds its weight to the light's own emission.
  void aim_finite(Emitter &e) const {
    e.own = 1, e.toward = 1, e.aims.clear();
    if (targets_.empty()) return;
    double inside = 0, total = 0;
    for (uint32_t t = 0; t < targets_.clusters.size(); ++t) {
      const Sphere &s = targets_.clusters[t].sphere;
      const EmissionCone cone = EmissionCone::towards(e.position, s.center, s.radius);
      if (!cone.active()) {
        inside += 4 * kPi, total += 4 * kPi;
        continue;
      }
      if (!in_spot(e, cone)) continue;
      const double solid_angle = 2 * kPi * double(cone.one_minus_cos);
      e.aims.push_back({t, float(solid_angle), cone});
      total += solid_angle;
    }
    e.toward = toward_objects(e);
    if (e.aims.empty()) return;
    e.own = float(kOwnShare + (1 - kOwnShare) * inside / total);
    for (Aim &a : e.aims) a.share = float((1 - kOwnShare) * double(a.share) / total);
  }
  // Whether a spot's cone can meet the cone towards a target (always, for other lights).
  static bool in_spot(const Emitter &e, const EmissionCone &cone) {
    if (e.kind != EmitterKind::Spot) return true;
    const float spot_angle = std::acos(std::clamp(e.cos_theta_e, -1.0f, 1.0f));
    const float apart = std::acos(std::clamp(dot(cone.axis, e.axis), -1.0f, 1.0f));
    return apart <= spot_angle + std::asin(std::sqrt(cone.sin2));
  }
  // The share of a finite light's power that leaves towards the sharp objects themselves (the clusters'
  // spheres when there are too many to list), taking its emission as uniform over the solid angle it
  // emits into (an area light's hemisphere): the flux its photons can bring to caustics. A light inside
  // a cluster's sphere emits at its own objects, not at the whole sphere.
  float toward_objects(const Emitter &e) const {
    const double emitted = e.kind == EmitterKind::Spot    ? 2 * kPi * double(1 - e.cos_theta_e)
                           : e.kind == EmitterKind::Point ? 4 * kPi
                                                          : 2 * kPi;
    double toward = 0;
    const auto add = [&](const Sphere &s) {
      const EmissionCone cone = EmissionCone::towards(e.position, s.center, s.radius);
      if (!cone.active())
        toward += emitted;
      else if (in_spot(e, cone))
        toward += std::min(2 * kPi * double(cone.one_minus_cos), emitted);
    };
    if (targets_.objects.empty())
      for (const Target &c : targets_.clusters) add(c.sphere);
    for (const Sphere &s : targets_.objects) add(s);
    return float(std::min(1.0, toward / emitted));
  }

  // The sun's footprint on the targets: their disk, or the rectangle around their box when smaller.
  void aim_sun(Emitter &e) const {
    e.own = 1, e.use_rect = false;
    if (targets_.empty() || !(targets_.all.sphere.radius < scene_radius_)) return;
    e.own = kOwnShare;
    e.pdf_pos = 1 / (kPi * sqr(disk_radius()));
    if (e.kind == EmitterKind::Sun) fit_rect(e, targets_.all.lo, targets_.all.hi);
  }

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
      const Vec3f d =
          Vec3f(c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z) - targets_.all.sphere.center;
      const float s = dot(d, f.s), t = dot(d, f.t);
      r[0] = std::min(r[0], s), r[1] = std::max(r[1], s), r[2] = std::min(r[2], t), r[3] = std::max(r[3], t);
      far = std::max(far, length(d));
    }
    // To first order the s axis turns by the half angle, the t axis by twice it: 3x for room.
    const float sin_half = e.delta_direction() ? 0.0f : std::sqrt(std::max(0.0f, 1 - sqr(e.cos_theta_e)));
    const float margin = 3 * sin_half * far + 1e-4f * scene_radius_;
    r[0] -= margin, r[1] += margin, r[2] -= margin, r[3] += margin;
    const float area = (r[1] - r[0]) * (r[3] - r[2]);
    if (!(area > 0) || !(area < kPi * sqr(disk_radius()))) return;
    e.use_rect = true, e.rect_s = f.s, e.pdf_pos = 1 / area;
    std::copy(r, r + 4, e.rect);
  }

  std::vector<Emitter> emitters_;
  std::vector<std::unique_ptr<const EnvironmentEmission>> environments_;  // per light; environments only
  SharpTargets targets_;
  uint32_t slots_ = 0;  // emission-map slots of all lights
  EmissionMap map_;
  const nimbus_host_t *host_ = nullptr;
  const nimbus_host_lights_v1_t *lights_ = nullptr;
  std::vector<double> rule_;  // photon power of each light (photon_powers)
  AliasTable table_;
  Vec3f scene_center_;
  float scene_radius_ = 1;
};

}  // namespace nimbus::caustics
