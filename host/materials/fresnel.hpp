// Unpolarised Fresnel reflectance of smooth boundaries. Part of scattering.hpp; include that.
#pragma once

#include <nimbus/cpp/math.hpp>
#include "materials/local_frame.hpp"

namespace nimbus {

// Exact reflectance of a dielectric boundary. cos_i is measured against the normal on the side whose IOR
// is 1 relative to `eta` (so a negative cos_i means the ray arrives from the eta side and the ratio flips),
// which lets callers pass dot(wo, n) without caring which side wo is on. 1 under total internal reflection.
inline float fresnel_dielectric(float cos_i, float eta) {
  cos_i = clamp(cos_i, -1.0f, 1.0f);
  if (cos_i < 0) eta = 1 / eta, cos_i = -cos_i;
  const float cos2_t = refracted_cos2(cos_i, eta);
  if (cos2_t <= 0) return 1.0f;
  const float cos_t = std::sqrt(cos2_t);
  // The textbook numerators (eta cos_i - cos_t, cos_i - eta cos_t) cancel catastrophically near eta = 1.
  // Multiplied out with Snell's law they become multiples of eta^2 - 1, computed exactly as
  // (eta - 1)(eta + 1), so a nearly index-matched boundary keeps its (tiny) reflectance accurate and
  // reciprocal. Neither denominator vanishes: cos_t > 0 here, and eta > 0.
  const float eta2 = eta * eta, eta2_minus_1 = (eta - 1) * (eta + 1);
  const float r_parl = eta2_minus_1 * ((eta2 + 1) * cos_i * cos_i - 1) / (eta2 * sqr(eta * cos_i + cos_t));
  const float r_perp = -eta2_minus_1 / sqr(cos_i + eta * cos_t);
  return std::min(1.0f, (r_parl * r_parl + r_perp * r_perp) / 2);
}

// Transmittance of a dielectric boundary for a refraction whose two cosines are both known (incident
// cos_i and refracted cos_t, magnitudes, eta = IOR on the cos_t side / IOR on the cos_i side):
// T = 2 eta cos_i cos_t (1 / (eta cos_i + cos_t)^2 + 1 / (cos_i + eta cos_t)^2). Rough refraction measures
// both cosines from the directions instead of deriving one by Snell's law, which near the critical angle
// keeps no correct digits (and 1 - R none either). The formula is symmetric under swapping the sides
// (cos_i <-> cos_t, eta -> 1/eta), so the rough BTDF is reciprocal to the last bit of its inputs.
inline float fresnel_dielectric_transmittance(float cos_i, float cos_t, float eta) {
  const float t_parl = 1 / sqr(eta * cos_i + cos_t), t_perp = 1 / sqr(cos_i + eta * cos_t);
  const float t = 2 * eta * cos_i * cos_t * (t_parl + t_perp);
  return std::isfinite(t) ? clamp(t, 0.0f, 1.0f) : 0.0f;
}

// Reflectance of a conductor with complex IOR eta + i k relative to the outside medium. cos_i is clamped
// to [0, 1]: conductors are opaque, so only the outside is ever lit. The complex Fresnel equations are
// expanded into real arithmetic (a^2 + b^2 = |n^2 - sin^2|, a = Re sqrt(n^2 - sin^2)): exact like the
// complex form, and several times faster than std::complex<float> division, which matters in eval().
inline float fresnel_complex(float cos_i, float eta, float k) {
  cos_i = clamp(cos_i, 0.0f, 1.0f);
  const float cos2 = cos_i * cos_i, sin2 = 1 - cos2;
  const float eta2 = eta * eta, k2 = k * k;
  const float t0 = eta2 - k2 - sin2;
  const float a2_plus_b2 = std::sqrt(t0 * t0 + 4 * eta2 * k2);
  const float a = safe_sqrt(0.5f * (a2_plus_b2 + t0));
  const float t1 = a2_plus_b2 + cos2, t2 = 2 * cos_i * a;
  const float r_perp = (t1 - t2) / (t1 + t2);
  const float t3 = cos2 * a2_plus_b2 + sin2 * sin2, t4 = t2 * sin2;
  const float r_parl = r_perp * (t3 - t4) / (t3 + t4);
  const float r = (r_perp + r_parl) / 2;
  // 0/0 only at grazing incidence with n = 1; the limit is total reflection.
  return std::isfinite(r) ? clamp(r, 0.0f, 1.0f) : 1.0f;
}

// Per RGB channel: the host renders RGB, so eta and k are RGB triples (scene/metals.hpp projects measured
// spectra onto them).
inline Rgb fresnel_complex(float cos_i, const Rgb &eta, const Rgb &k) {
  return {fresnel_complex(cos_i, eta.x, k.x), fresnel_complex(cos_i, eta.y, k.y),
          fresnel_complex(cos_i, eta.z, k.z)};
}

}  // namespace nimbus
