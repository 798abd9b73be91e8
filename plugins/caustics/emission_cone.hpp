// A cone of directions with a uniform density: how photons of finite lights are aimed at a sphere of
// sharp geometry (projection maps, solver spec 6.2).
#pragma once

#include <algorithm>
#include <cmath>

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
  // The (u0, u1) that sample() maps to the unit direction w, which the cone contains (the adaptive
  // emission map's coordinates, emission_map.hpp).
  Vec2f invert(const Vec3f &w) const {
    const Vec3f l = Frame::from_normal(axis).to_local(w);
    const float t = (l.x * l.x + l.y * l.y) / (1.0f + std::max(l.z, 0.0f));  // 1 - cos, no cancellation
    float phi = std::atan2(l.y, l.x);
    if (phi < 0) phi += 2.0f * kPi;
    constexpr float kBelowOne = 0x1.fffffep-1f;
    return {std::min(t / one_minus_cos, kBelowOne), std::min(phi / (2.0f * kPi), kBelowOne)};
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

}  // namespace nimbus::caustics
