#include "light_bounds.hpp"

namespace nimbus::lights {
namespace {

// cos(max(0, a - b)) and sin(max(0, a - b)) from the sines and cosines of a and b.
float cos_sub_clamped(float sin_a, float cos_a, float sin_b, float cos_b) {
  return cos_a > cos_b ? 1.0f : cos_a * cos_b + sin_a * sin_b;
}
float sin_sub_clamped(float sin_a, float cos_a, float sin_b, float cos_b) {
  return cos_a > cos_b ? 0.0f : sin_a * cos_b - cos_a * sin_b;
}

// Rotation of v about the unit axis by angle (Rodrigues).
Vec3f rotate(const Vec3f &v, const Vec3f &axis, float angle) {
  const float c = std::cos(angle), s = std::sin(angle);
  return v * c + cross(axis, v) * s + axis * (dot(axis, v) * (1 - c));
}

}  // namespace

DirectionCone cone_union(const DirectionCone &a, const DirectionCone &b) {
  if (a.empty()) return b;
  if (b.empty()) return a;
  const float theta_a = std::acos(clamp(a.cos_theta, -1, 1)), theta_b = std::acos(clamp(b.cos_theta, -1, 1));
  const float theta_d = std::acos(clamp(dot(a.w, b.w), -1, 1));
  if (std::min(theta_d + theta_b, kPi) <= theta_a) return a;
  if (std::min(theta_d + theta_a, kPi) <= theta_b) return b;
  const float theta_o = (theta_a + theta_d + theta_b) / 2;
  if (theta_o >= kPi) return DirectionCone::sphere();
  const Vec3f wr = cross(a.w, b.w);
  if (length_squared(wr) == 0) return DirectionCone::sphere();
  const Vec3f w = rotate(a.w, normalize(wr), theta_o - theta_a);
  return {normalize(w), std::cos(theta_o)};
}

LightBounds bounds_union(const LightBounds &a, const LightBounds &b) {
  if (a.phi == 0) return b;
  if (b.phi == 0) return a;
  LightBounds u;
  u.lo = min(a.lo, b.lo), u.hi = max(a.hi, b.hi);
  u.phi = a.phi + b.phi;
  u.normals = cone_union(a.normals, b.normals);
  u.cos_theta_e = std::min(a.cos_theta_e, b.cos_theta_e);
  u.two_sided = a.two_sided || b.two_sided;
  return u;
}

NodeBounds::NodeBounds(const LightBounds &b)
    : centroid(b.centroid()),
      axis(b.normals.w),
      phi(b.phi),
      radius(length(b.hi - b.lo) / 2),
      radius2(radius * radius),
      cos_o(b.normals.cos_theta),
      sin_o(safe_sqrt(1 - b.normals.cos_theta * b.normals.cos_theta)),
      cos_e(b.cos_theta_e),
      two_sided(b.two_sided) {}

float NodeBounds::importance(const Vec3f &p, const Vec3f &n) const {
  const Vec3f d = p - centroid;
  const float dist2 = length_squared(d);
  const float d2 = std::max(dist2, radius);
  const float inv_dist = dist2 > 0 ? 1 / std::sqrt(dist2) : 0.0f;
  const Vec3f wi = d * inv_dist;
  float cos_w = dist2 > 0 ? dot(axis, wi) : 1.0f;  // p at the centroid: any direction
  if (two_sided) cos_w = std::abs(cos_w);
  const float sin_w = safe_sqrt(1 - cos_w * cos_w);
  // Bound on the angle the box subtends from p (all directions when p is inside its sphere).
  float cos_b = -1, sin_b = 0;
  if (dist2 > radius2) sin_b = std::min(radius * inv_dist, 1.0f), cos_b = safe_sqrt(1 - sin_b * sin_b);
  const float cos_x = cos_sub_clamped(sin_w, cos_w, sin_o, cos_o);
  const float sin_x = sin_sub_clamped(sin_w, cos_w, sin_o, cos_o);
  const float cos_p = cos_sub_clamped(sin_x, cos_x, sin_b, cos_b);
  if (cos_p <= cos_e) return 0;
  float imp = phi * cos_p / d2;
  if (!is_black(n)) {
    const float cos_i = std::abs(dot(wi, n)), sin_i = safe_sqrt(1 - cos_i * cos_i);
    imp *= cos_sub_clamped(sin_i, cos_i, sin_b, cos_b);
  }
  return std::max(imp, 0.0f);
}

LightBounds bounds_of(const nimbus_light_info_t &info) {
  LightBounds b;
  if (info.flags & NIMBUS_LIGHT_INFINITE) return b;
  b.lo = Vec3f::load(info.bounds_min), b.hi = Vec3f::load(info.bounds_max);
  b.phi = std::isfinite(info.power) && info.power > 0 ? info.power : 0;
  const Vec3f axis = Vec3f::load(info.axis);
  b.normals = is_black(axis) || info.cos_theta_o <= -1 ? DirectionCone::sphere()
                                                       : DirectionCone{normalize(axis), info.cos_theta_o};
  b.cos_theta_e = info.cos_theta_e;
  b.two_sided = (info.flags & NIMBUS_LIGHT_TWO_SIDED) != 0;
  return b;
}

}  // namespace nimbus::lights
