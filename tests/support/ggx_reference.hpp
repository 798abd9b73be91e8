// A reference GGX microfacet model for tests, written from the published formulas in double precision and
// sharing no code with materials/: Trowbridge-Reitz (GGX) D through Smith's G1 (Walter et al. 2007),
// Heitz's (2018) map of the visible normals, and the unpolarised Fresnel equations of a dielectric. Its
// scattering weight uses the uncorrelated masking-shadowing G1(wo) G1(wi), which never exceeds the
// height-correlated G2 = 1 / (1 + Lambda(wo) + Lambda(wi)) since (1 + Lo)(1 + Li) >= 1 + Lo + Li, so
// what it integrates is a lower bound of what a correct height-correlated GGX keeps.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

namespace nimbus::reference {

using V3 = std::array<double, 3>;

inline double dot3(const V3 &a, const V3 &b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline V3 axpy(double a, const V3 &x, const V3 &y) {
  return {a * x[0] + y[0], a * x[1] + y[1], a * x[2] + y[2]};
}
inline V3 scale(double a, const V3 &x) { return {a * x[0], a * x[1], a * x[2]}; }
inline V3 unit(const V3 &a) { return scale(1 / std::sqrt(dot3(a, a)), a); }
inline V3 cross3(const V3 &a, const V3 &b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// Smith's masking of direction w (local frame, normal +z) by a GGX surface of roughness alpha.
inline double smith_g1(const V3 &w, double alpha) {
  const double c2 = w[2] * w[2];
  if (c2 == 0) return 0;
  return 2 / (1 + std::sqrt(1 + alpha * alpha * (1 - c2) / c2));
}

// Smith's Lambda of direction w: G1 = 1 / (1 + Lambda), and the height-correlated masking-shadowing of a
// pair is G2 = 1 / (1 + Lambda(wo) + Lambda(wi)) (Heitz 2014).
inline double smith_lambda(const V3 &w, double alpha) {
  const double c2 = w[2] * w[2];
  if (c2 == 0) return 1e300;
  return 0.5 * (std::sqrt(1 + alpha * alpha * (1 - c2) / c2) - 1);
}

// The microfacet normal at (u1, u2) of Heitz's map, wo in the upper hemisphere: uniform (u1, u2) give the
// normals visible from wo, with density G1(wo) max(0, wo.m) D(m) / cos(wo).
inline V3 visible_normal(const V3 &wo, double alpha, double u1, double u2) {
  const V3 vh = unit({alpha * wo[0], alpha * wo[1], wo[2]});
  const double len = std::hypot(vh[0], vh[1]);
  const V3 t1 = len > 0 ? V3{-vh[1] / len, vh[0] / len, 0} : V3{1, 0, 0};
  const V3 t2 = cross3(vh, t1);
  const double r = std::sqrt(u1), phi = 2 * 3.14159265358979323846 * u2;
  const double p1 = r * std::cos(phi), s = 0.5 * (1 + vh[2]);
  const double p2 = (1 - s) * std::sqrt(1 - p1 * p1) + s * r * std::sin(phi);
  const double p3 = std::sqrt(std::max(0.0, 1 - p1 * p1 - p2 * p2));
  const V3 nh = axpy(p1, t1, axpy(p2, t2, scale(p3, vh)));
  return unit({alpha * nh[0], alpha * nh[1], std::max(0.0, nh[2])});
}

// Unpolarised Fresnel reflectance at a facet, cos_i > 0, etap = IOR beyond over IOR before; sets cos_t
// (the refracted cosine) unless the light is totally reflected (then 1).
inline double fresnel(double cos_i, double etap, double *cos_t) {
  const double sin2_t = (1 - cos_i * cos_i) / (etap * etap);
  if (sin2_t >= 1) return 1;
  *cos_t = std::sqrt(1 - sin2_t);
  const double par = (etap * cos_i - *cos_t) / (etap * cos_i + *cos_t);
  const double perp = (cos_i - etap * *cos_t) / (cos_i + etap * *cos_t);
  return 0.5 * (par * par + perp * perp);
}

// One bounce off the microsurface from wo (local frame, either side; pointing away from the surface):
// the reflected and refracted directions at the visible normal m(u1, u2), their Fresnel split, and each
// one's lower-bound weight G1(wi) (zero for a direction on the wrong side, which no single facet can
// produce). The albedo in importance transport (what the surface keeps) is at least
// E_m[F w_reflect + (1 - F) w_refract]. eta is the index inside (z < 0) over outside; 0 makes an ideal
// mirror (F = 1). Below the surface the microsurface is the same one seen mirrored, with index 1 / eta.
struct Bounce {
  V3 reflected{}, refracted{};
  double fresnel = 1, w_reflect = 0, w_refract = 0;
  // The weights G2(wo, wi) / G1(wo) of the height-correlated form itself, at least the ones above.
  double w_reflect_correlated = 0, w_refract_correlated = 0;
};

inline Bounce bounce(const V3 &w, double eta, double alpha, double u1, double u2) {
  const double side = w[2] >= 0 ? 1 : -1;
  const V3 wo{w[0], w[1], side * w[2]};
  const double etap = side > 0 ? eta : 1 / eta;
  const V3 m = visible_normal(wo, alpha, u1, u2);
  Bounce b;
  const double c = dot3(wo, m);
  if (!(c > 0)) return b;
  double cos_t = 0;
  b.fresnel = eta == 0 ? 1 : fresnel(c, etap, &cos_t);
  b.reflected = axpy(2 * c, m, scale(-1, wo));
  const double lo = smith_lambda(wo, alpha);
  const auto correlated = [&](const V3 &wi) { return (1 + lo) / (1 + lo + smith_lambda(wi, alpha)); };
  if (b.reflected[2] > 0) {
    b.w_reflect = smith_g1(b.reflected, alpha);
    b.w_reflect_correlated = correlated(b.reflected);
  }
  if (b.fresnel < 1) {
    b.refracted = axpy(c / etap - cos_t, m, scale(-1 / etap, wo));
    if (b.refracted[2] < 0) {
      b.w_refract = smith_g1(b.refracted, alpha);
      b.w_refract_correlated = correlated(b.refracted);
    }
  }
  b.reflected[2] *= side, b.refracted[2] *= side;
  return b;
}

}  // namespace nimbus::reference
