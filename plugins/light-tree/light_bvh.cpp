#include "light_bounds.hpp"

#include <cstring>
#if defined(__SSE__)
#include <xmmintrin.h>
#endif

namespace nimbus::lights {
namespace {

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

void WideNode::set(int k, const LightBounds &b, uint32_t child_index, bool leaf) {
  const Vec3f c = b.centroid();
  cx[k] = c.x, cy[k] = c.y, cz[k] = c.z;
  radius[k] = length(b.hi - b.lo) / 2, radius2[k] = radius[k] * radius[k];
  ax[k] = b.normals.w.x, ay[k] = b.normals.w.y, az[k] = b.normals.w.z;
  cos_o[k] = b.normals.cos_theta, sin_o[k] = safe_sqrt(1 - b.normals.cos_theta * b.normals.cos_theta);
  cos_e[k] = b.cos_theta_e;
  phi[k] = b.phi;
  two_sided[k] = b.two_sided ? -1 : 0;
  child[k] = child_index;
  leaf_mask = uint8_t(leaf ? leaf_mask | (1u << k) : leaf_mask & ~(1u << k));
}

namespace {

// Four lanes through GCC's vector extensions (SSE on x86-64, NEON on arm64; +, *, /, comparisons and
// ?: act lane by lane).
typedef float F4 __attribute__((vector_size(16)));
typedef int32_t M4 __attribute__((vector_size(16)));

F4 load(const float *p) {
  F4 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
F4 splat(float x) { return F4{x, x, x, x}; }
F4 max4(F4 a, F4 b) { return a > b ? a : b; }  // NaN in a gives b
F4 min4(F4 a, F4 b) { return a < b ? a : b; }
F4 abs4(F4 a) { return a < 0 ? -a : a; }
F4 sqrt4(F4 a) {
#if defined(__SSE__)
  return _mm_sqrt_ps(a);
#else
  return F4{std::sqrt(a[0]), std::sqrt(a[1]), std::sqrt(a[2]), std::sqrt(a[3])};
#endif
}
F4 safe_sqrt4(F4 a) { return sqrt4(max4(a, splat(0))); }
// cos(max(0, a - b)) and sin(max(0, a - b)) from the sines and cosines of a and b.
F4 cos_sub_clamped(F4 sin_a, F4 cos_a, F4 sin_b, F4 cos_b) {
  return cos_a > cos_b ? splat(1) : cos_a * cos_b + sin_a * sin_b;
}
F4 sin_sub_clamped(F4 sin_a, F4 cos_a, F4 sin_b, F4 cos_b) {
  return cos_a > cos_b ? splat(0) : sin_a * cos_b - cos_a * sin_b;
}

}  // namespace

void WideNode::importance(const Vec3f &p, const Vec3f &n, float out[kWidth]) const {
  const F4 dx = splat(p.x) - load(cx), dy = splat(p.y) - load(cy), dz = splat(p.z) - load(cz);
  const F4 dist2 = dx * dx + dy * dy + dz * dz, r = load(radius);
  const F4 d2 = max4(dist2, r);
  const M4 apart = dist2 > 0;
  const F4 inv_dist = apart ? splat(1) / sqrt4(dist2) : splat(0);
  const F4 wx = dx * inv_dist, wy = dy * inv_dist, wz = dz * inv_dist;
  F4 cos_w = apart ? load(ax) * wx + load(ay) * wy + load(az) * wz : splat(1);  // p at the centroid: any
  M4 two;
  std::memcpy(&two, two_sided, sizeof two);
  cos_w = two ? abs4(cos_w) : cos_w;
  const F4 sin_w = safe_sqrt4(1 - cos_w * cos_w);
  // Bound on the angle the box subtends from p (all directions when p is inside its sphere).
  const M4 outside = dist2 > load(radius2);
  const F4 sin_b = outside ? min4(r * inv_dist, splat(1)) : splat(0);
  const F4 cos_b = outside ? safe_sqrt4(1 - sin_b * sin_b) : splat(-1);
  const F4 co = load(cos_o), so = load(sin_o);
  const F4 cos_x = cos_sub_clamped(sin_w, cos_w, so, co), sin_x = sin_sub_clamped(sin_w, cos_w, so, co);
  const F4 cos_p = cos_sub_clamped(sin_x, cos_x, sin_b, cos_b);
  F4 imp = load(phi) * cos_p / d2;
  if (!is_black(n)) {
    const F4 cos_i = abs4(wx * n.x + wy * n.y + wz * n.z), sin_i = safe_sqrt4(1 - cos_i * cos_i);
    imp *= cos_sub_clamped(sin_i, cos_i, sin_b, cos_b);
  }
  // Zero outside the emission cone, for empty lanes, and where rounding made it negative or NaN.
  imp = cos_p > load(cos_e) ? max4(imp, splat(0)) : splat(0);
  std::memcpy(out, &imp, sizeof imp);
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
