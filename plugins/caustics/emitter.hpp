// One light as the caustics solver sees it: its kind (from the host's info flags), LightMix group, power
// and projection map (emitters.hpp builds the maps and the densities from them).
#pragma once

#include <nimbus/lights.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include <nimbus/cpp/math.hpp>

#include "emission_cone.hpp"

namespace nimbus::caustics {

// The share of a light's photons emitted as the light itself emits (finite lights), or from the scene's
// whole disk (the sun): a defence against bounds that miss a caustic-forming surface.
inline constexpr float kOwnShare = 0.1f;

enum class EmitterKind : uint8_t { Area, Point, Spot, Sun, Environment };

// One cone of a finite light's projection map.
struct Aim {
  uint32_t target = 0;  // index into the targets
  float share = 0;      // probability of this component
  EmissionCone cone;    // point, spot: from the light's position (area lights: from each emission point)
};

struct Emitter {
  EmitterKind kind = EmitterKind::Point;
  uint32_t flags = 0, group = 0;
  float power = 0;
  Vec3f axis;               // spot: the cone axis; sun: the direction photons travel
  float cos_theta_e = -1;   // spot / sun cone
  Vec3f position;           // point, spot; area: the centre of its bounds
  Vec3f lo, hi;             // world bounds (finite lights)
  float own = 1;            // share of the light's own emission (finite) or of the scene's disk (sun)
  float toward = 1;         // finite: share of its power that leaves towards the targets (aim_finite)
  uint32_t first_slot = 0;  // its first emission-map slot: one per aim (finite), one for the targets' disk
  std::vector<Aim> aims;    // finite lights: the cones towards the targets
  // sun: 1 / the area of the targets' disk or rectangle; the rectangle [s0, s1] x [t0, t1] around the
  // targets' centre lies in the plane perpendicular to each direction w, in the basis of w whose s axis
  // follows rect_s; unused (the disk) where the disk is smaller.
  float pdf_pos = 0;
  bool use_rect = false;
  Vec3f rect_s;
  float rect[4] = {0, 0, 0, 0};  // s0, s1, t0, t1
  bool delta_position() const { return flags & NIMBUS_LIGHT_DELTA_POSITION; }
  bool moves() const { return flags & NIMBUS_LIGHT_MOVES; }  // a point or spot light (SDK 1.7)
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
  e.lo = Vec3f::load(info.bounds_min), e.hi = Vec3f::load(info.bounds_max);
  e.position = (e.lo + e.hi) * 0.5f;
  const bool has_axis = !is_black(e.axis);
  if (info.flags & NIMBUS_LIGHT_AREA)
    e.kind = EmitterKind::Area;
  else if (info.flags & NIMBUS_LIGHT_INFINITE)
    e.kind = has_axis && info.cos_theta_o >= 1 ? EmitterKind::Sun : EmitterKind::Environment;
  else
    e.kind = has_axis && info.cos_theta_o >= 1 ? EmitterKind::Spot : EmitterKind::Point;
  return e;
}

}  // namespace nimbus::caustics
