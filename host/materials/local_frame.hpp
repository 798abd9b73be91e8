// Trigonometry of unit directions in the local shading frame (z = shading normal), and the two ideal
// scattering directions. Part of scattering.hpp; include that.
#pragma once

#include <optional>

#include <nimbus/cpp/math.hpp>

namespace nimbus {

inline float cos_theta(const Vec3f &w) { return w.z; }
inline float cos2_theta(const Vec3f &w) { return w.z * w.z; }
inline float abs_cos_theta(const Vec3f &w) { return std::abs(w.z); }
// From x and y rather than 1 - cos^2: near the pole cos rounds to 1 while x and y keep full precision,
// which matters for GGX lobes only 1e-4 wide.
inline float sin2_theta(const Vec3f &w) { return w.x * w.x + w.y * w.y; }
inline float sin_theta(const Vec3f &w) { return std::sqrt(sin2_theta(w)); }
// +Inf at the horizon.
inline float tan2_theta(const Vec3f &w) { return sin2_theta(w) / cos2_theta(w); }
inline float cos_phi(const Vec3f &w) {
  const float s = sin_theta(w);
  return s == 0 ? 1.0f : clamp(w.x / s, -1.0f, 1.0f);
}
inline float sin_phi(const Vec3f &w) {
  const float s = sin_theta(w);
  return s == 0 ? 0.0f : clamp(w.y / s, -1.0f, 1.0f);
}
// Strictly: a direction in the tangent plane is on neither side.
inline bool same_hemisphere(const Vec3f &a, const Vec3f &b) { return a.z * b.z > 0; }
inline float abs_dot(const Vec3f &a, const Vec3f &b) { return std::abs(dot(a, b)); }
// v flipped, if needed, into the hemisphere around `ref`.
inline Vec3f face_forward(const Vec3f &v, const Vec3f &ref) { return dot(v, ref) < 0 ? -v : v; }

// Mirror of wo about n (both unit; the result points away from the surface like wo).
inline Vec3f reflect(const Vec3f &wo, const Vec3f &n) { return -wo + n * (2 * dot(wo, n)); }

// cos^2 of the refracted angle for an incident cos_i >= 0 and relative IOR eta (Snell), <= 0 under total
// internal reflection. Written as (eta^2 - 1 + cos_i^2) / eta^2 rather than 1 - sin_i^2 / eta^2: no
// cancellation at grazing incidence or near eta = 1. fresnel_dielectric() and refract() both decide total
// internal reflection here, so they always agree.
inline float refracted_cos2(float cos_i, float eta) {
  return ((eta - 1) * (eta + 1) + cos_i * cos_i) / (eta * eta);
}

struct Refraction {
  Vec3f wt;        // transmitted direction, unit length
  float etap = 1;  // relative IOR actually crossed: eta from n's side, 1/eta from the other
};

// Snell refraction of wi (pointing away from the surface) through a boundary with normal n, where eta is
// the IOR ratio (side opposite to n) / (side of n). wi may be on either side of n. Empty on total internal
// reflection. The TIR test matches fresnel_dielectric() exactly, so a refraction is offered whenever the
// Fresnel transmittance is non-zero.
inline std::optional<Refraction> refract(const Vec3f &wi, Vec3f n, float eta) {
  float cos_i = dot(n, wi);
  if (cos_i < 0) eta = 1 / eta, cos_i = -cos_i, n = -n;
  cos_i = std::min(cos_i, 1.0f);
  const float cos2_t = refracted_cos2(cos_i, eta);
  if (cos2_t <= 0) return std::nullopt;
  const float cos_t = std::sqrt(cos2_t);
  return Refraction{-wi / eta + n * (cos_i / eta - cos_t), eta};
}

}  // namespace nimbus
