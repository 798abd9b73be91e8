// Warps from the unit square to common domains, with their densities (pbrt-v4, ch. A.5).
#pragma once

#include <algorithm>
#include <cmath>

#include <nimbus/cpp/math.hpp>

namespace nimbus {

// cos and sin of an angle in [-pi/4, pi/4]: Cephes' minimax polynomials for that interval, within 1.5 ulps,
// inline: libm's sincosf reduces arguments of any size and costs more than the rest of a diffuse sample.
inline Vec2f cos_sin_quarter(float a) {
  const float z = a * a;
  const float c = 1.0f - 0.5f * z +
                  z * z * (4.166664568298827e-2f + z * (-1.388731625493765e-3f + z * 2.443315711809948e-5f));
  const float s = a + a * z * (-1.6666654611e-1f + z * (8.3321608736e-3f + z * -1.9515295891e-4f));
  return {c, s};
}

// Concentric (Shirley-Chiu) mapping of [0,1)^2 onto the unit disk. The angle of the second pair of
// sectors, pi/2 - phi, is taken as (sin phi, cos phi): both branches evaluate an angle within pi/4.
inline Vec2f sample_uniform_disk_concentric(float u0, float u1) {
  const float ox = 2.0f * u0 - 1.0f, oy = 2.0f * u1 - 1.0f;
  if (ox == 0 && oy == 0) return {0, 0};
  if (std::abs(ox) > std::abs(oy)) {
    const Vec2f cs = cos_sin_quarter((kPi / 4) * (oy / ox));
    return {ox * cs.x, ox * cs.y};
  }
  const Vec2f cs = cos_sin_quarter((kPi / 4) * (ox / oy));
  return {oy * cs.y, oy * cs.x};
}

// The (u0, u1) that sample_uniform_disk_concentric maps to the point p of the unit disk (pbrt-v4's
// InvertUniformDiskConcentricSample): how a density over (u0, u1) is evaluated at a point.
inline Vec2f invert_uniform_disk_concentric(const Vec2f &p) {
  const float r = std::sqrt(p.x * p.x + p.y * p.y);
  if (!(r > 0)) return {0.5f, 0.5f};
  const float theta = std::atan2(p.y, p.x), k = 4 / kPi;  // theta in [-pi, pi]
  float ox, oy;
  if (std::abs(theta) <= kPi / 4) {
    ox = r, oy = r * theta * k;
  } else if (std::abs(theta) >= 3 * kPi / 4) {
    ox = -r, oy = ox * (theta > 0 ? theta - kPi : theta + kPi) * k;
  } else if (theta > 0) {
    oy = r, ox = oy * (kPi / 2 - theta) * k;
  } else {
    oy = -r, ox = oy * (kPi / 2 - (theta + kPi)) * k;
  }
  return {std::clamp(0.5f * (ox + 1), 0.0f, 0x1.fffffep-1f),
          std::clamp(0.5f * (oy + 1), 0.0f, 0x1.fffffep-1f)};
}

inline Vec3f sample_cosine_hemisphere(float u0, float u1) {
  const Vec2f d = sample_uniform_disk_concentric(u0, u1);
  return {d.x, d.y, safe_sqrt(1.0f - d.x * d.x - d.y * d.y)};
}
inline float cosine_hemisphere_pdf(float cos_theta) { return std::max(cos_theta, 0.0f) * kInvPi; }

inline Vec3f sample_uniform_sphere(float u0, float u1) {
  const float z = 1.0f - 2.0f * u0;
  const float r = safe_sqrt(1.0f - z * z);
  const float phi = 2.0f * kPi * u1;
  return {r * std::cos(phi), r * std::sin(phi), z};
}
inline constexpr float kUniformSpherePdf = 1.0f / (4.0f * kPi);

// Uniform direction in the cone around +z whose half angle theta_max has 1 - cos(theta_max) =
// one_minus_cos. Taking 1 - cos rather than cos keeps narrow cones (a small target seen from far away,
// where cos rounds to 1 in float) exact: sin(theta) comes from t (2 - t), not from 1 - cos^2.
inline Vec3f sample_uniform_cone_narrow(float u0, float u1, float one_minus_cos) {
  const float t = u0 * one_minus_cos;  // 1 - cos(theta), uniform in [0, one_minus_cos)
  const float sin_theta = safe_sqrt(t * (2.0f - t));
  const float phi = u1 * 2.0f * kPi;
  return {std::cos(phi) * sin_theta, std::sin(phi) * sin_theta, 1.0f - t};
}
inline float uniform_cone_pdf_narrow(float one_minus_cos) { return 1.0f / (2.0f * kPi * one_minus_cos); }

// Uniform direction in the cone around +z with the given cos of its half angle.
inline Vec3f sample_uniform_cone(float u0, float u1, float cos_theta_max) {
  return sample_uniform_cone_narrow(u0, u1, 1.0f - cos_theta_max);
}
inline float uniform_cone_pdf(float cos_theta_max) { return uniform_cone_pdf_narrow(1.0f - cos_theta_max); }

// Barycentrics (b1, b2) uniform over a triangle (Heitz 2019's low-distortion map, as pbrt-v4).
inline Vec2f sample_uniform_triangle(float u0, float u1) {
  float b0, b1;
  if (u0 < u1) {
    b0 = u0 / 2, b1 = u1 - b0;
  } else {
    b1 = u1 / 2, b0 = u0 - b1;
  }
  return {b0, b1};
}

// Veach's power heuristic with beta = 2 for two techniques with one sample each.
inline float power_heuristic(float pdf_a, float pdf_b) {
  const float a = pdf_a * pdf_a, b = pdf_b * pdf_b;
  if (std::isinf(a)) return 1.0f;
  return a + b > 0 ? a / (a + b) : 0.0f;
}

}  // namespace nimbus
