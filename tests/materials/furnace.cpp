#include "furnace.hpp"

#include <array>

namespace nimbus::test {

namespace {

// Everything below is written from the published formulas, in double precision, and shares no code with
// materials/: Trowbridge-Reitz (GGX) D and Smith Lambda (Walter et al. 2007), Heitz's (2018) visible-normal
// parametrisation, and the unpolarised Fresnel equations.
using V3 = std::array<double, 3>;

double dot3(const V3 &a, const V3 &b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
V3 unit(const V3 &a) {
  const double l = std::sqrt(dot3(a, a));
  return {a[0] / l, a[1] / l, a[2] / l};
}

// Smith's masking of one direction by a GGX surface of roughness alpha.
double smith_g1(const V3 &w, double alpha) {
  const double c2 = w[2] * w[2];
  if (c2 == 0) return 0;
  const double tan2 = (1 - c2) / c2;
  return 2 / (1 + std::sqrt(1 + alpha * alpha * tan2));
}

// The microfacet normal at (u1, u2) of Heitz's map: uniform (u1, u2) give the normals visible from wo
// (upper hemisphere) with density G1(wo) max(0, wo.m) D(m) / cos(wo).
V3 visible_normal(const V3 &wo, double alpha, double u1, double u2) {
  const V3 vh = unit({alpha * wo[0], alpha * wo[1], wo[2]});
  const double len2 = vh[0] * vh[0] + vh[1] * vh[1];
  const V3 t1 = len2 > 0 ? V3{-vh[1] / std::sqrt(len2), vh[0] / std::sqrt(len2), 0} : V3{1, 0, 0};
  const V3 t2{vh[1] * t1[2] - vh[2] * t1[1], vh[2] * t1[0] - vh[0] * t1[2], vh[0] * t1[1] - vh[1] * t1[0]};
  const double r = std::sqrt(u1), phi = 2 * 3.14159265358979323846 * u2;
  const double p1 = r * std::cos(phi), s = 0.5 * (1 + vh[2]);
  const double p2 = (1 - s) * std::sqrt(1 - p1 * p1) + s * r * std::sin(phi);
  const double p3 = std::sqrt(std::max(0.0, 1 - p1 * p1 - p2 * p2));
  const V3 nh{p1 * t1[0] + p2 * t2[0] + p3 * vh[0], p1 * t1[1] + p2 * t2[1] + p3 * vh[1],
              p1 * t1[2] + p2 * t2[2] + p3 * vh[2]};
  return unit({alpha * nh[0], alpha * nh[1], std::max(0.0, nh[2])});
}

// Unpolarised Fresnel reflectance at a microfacet, cos_i > 0, etap = IOR beyond over IOR before; sets
// cos_t (the refracted cosine) unless the light is totally reflected.
double fresnel(double cos_i, double etap, double *cos_t) {
  const double sin2_t = (1 - cos_i * cos_i) / (etap * etap);
  if (sin2_t >= 1) return 1;
  *cos_t = std::sqrt(1 - sin2_t);
  const double par = (etap * cos_i - *cos_t) / (etap * cos_i + *cos_t);
  const double perp = (cos_i - etap * *cos_t) / (cos_i + etap * *cos_t);
  return 0.5 * (par * par + perp * perp);
}

}  // namespace

double ggx_albedo_lower_bound(double eta, double alpha, const Vec3f &w, int n) {
  // Below the surface the microsurface is the same one seen mirrored, with the inverse index.
  const V3 wo = unit({w.x, w.y, std::abs(double(w.z))});
  const double etap = w.z >= 0 ? eta : 1 / eta;
  double sum = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const V3 m = visible_normal(wo, alpha, (i + 0.5) / n, (j + 0.5) / n);
      const double c = dot3(wo, m);
      if (!(c > 0)) continue;
      double cos_t = 0;
      const double f = eta == 0 ? 1 : fresnel(c, etap, &cos_t);
      const V3 wr{2 * c * m[0] - wo[0], 2 * c * m[1] - wo[1], 2 * c * m[2] - wo[2]};
      if (wr[2] > 0) sum += f * smith_g1(wr, alpha);
      if (f < 1) {
        const double b = c / etap - cos_t;
        const V3 wt{-wo[0] / etap + b * m[0], -wo[1] / etap + b * m[1], -wo[2] / etap + b * m[2]};
        if (wt[2] < 0) sum += (1 - f) * smith_g1(wt, alpha);
      }
    }
  return sum / (double(n) * n);
}

}  // namespace nimbus::test
