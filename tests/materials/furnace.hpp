// White-furnace estimates shared by the energy tests: the directional albedo E[f |cos| / pdf] of a BSDF
// from its sampler or from its eval() alone, and the floor single-scattering GGX keeps above. Templates,
// so that the RGB BSDFs and the BSDFs at one wavelength (SpectralBsdf, scalar values) go through the same
// estimators.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <nimbus/cpp/sampling.hpp>
#include "test_helpers.hpp"

namespace nimbus::test {

struct Estimate {
  double mean = 0, std_error = 0;
  double reflected = 0;  // fraction of valid samples that reflected
};

// The first channel of a value: the materials tested by albedo are grey, and spectral values are scalars.
inline double first_channel(const Rgb &v) { return v.x; }
inline double first_channel(float v) { return v; }

// Monte Carlo directional albedo of the first channel from sample().
template <class B>
Estimate albedo_by_sampling(const B &bsdf, const Vec3f &wo, TransportMode mode, int n, uint64_t seed) {
  Pcg32 rng(seed);
  double sum = 0, sum2 = 0, reflected = 0;
  const int sqrt_n = static_cast<int>(std::sqrt(n));
  for (int i = 0; i < sqrt_n; ++i)
    for (int j = 0; j < sqrt_n; ++j) {
      // Stratified u: the variance of the rough lobes comes mostly from u, uc is cheap to leave random.
      const Vec2f u{(i + rng.uniform()) / sqrt_n, (j + rng.uniform()) / sqrt_n};
      const BsdfSample s = bsdf.sample(wo, rng.uniform(), u, mode);
      if (s.pdf == 0) continue;
      const double w = s.f.x * abs_cos_theta(s.wi) / s.pdf;
      sum += w, sum2 += w * w;
      reflected += same_hemisphere(wo, s.wi);
    }
  const double count = static_cast<double>(sqrt_n) * sqrt_n;
  Estimate e;
  e.mean = sum / count;
  e.std_error = std::sqrt(std::max(0.0, sum2 / count - e.mean * e.mean) / count);
  e.reflected = reflected / count;
  return e;
}

// The same albedo from eval() alone, with uniform sphere sampling: independent of sample().
template <class B>
Estimate albedo_by_eval(const B &bsdf, const Vec3f &wo, TransportMode mode, int n, uint64_t seed) {
  Pcg32 rng(seed);
  double sum = 0, sum2 = 0;
  for (int i = 0; i < n; ++i) {
    const Vec3f wi = sample_uniform_sphere(rng.uniform(), rng.uniform());
    const double w =
        first_channel(bsdf.eval(wo, wi, mode, nullptr, nullptr)) * abs_cos_theta(wi) / kUniformSpherePdf;
    sum += w, sum2 += w * w;
  }
  Estimate e;
  e.mean = sum / n;
  e.std_error = std::sqrt(std::max(0.0, sum2 / n - e.mean * e.mean) / n);
  return e;
}

// A lower bound of single-scattering GGX's directional albedo E[f |cos| / pdf] in importance transport
// (the energy a surface keeps), for a dielectric of index `eta` (inside over outside) or, with eta 0, an
// ideal mirror: support/ggx_reference.hpp's bounce integrated over the visible normals by an n x n midpoint
// rule, independent of materials/. Whatever the masking-shadowing form, the albedo is
// E_m[F G2(wo, wi) / G1(wo)] over the visible normals m, and G1(wi) lower-bounds G2 / G1(wo); the bound
// is exact at normal incidence, where Lambda(wo) = 0.
double ggx_albedo_lower_bound(double eta, double alpha, const Vec3f &wo, int n = 256);

// The same integral with the height-correlated G2 / G1(wo) itself: the albedo a correct single-scattering
// GGX with height-correlated masking-shadowing (the form materials/microfacet.hpp documents) has.
double ggx_albedo_height_correlated(double eta, double alpha, const Vec3f &wo, int n = 256);

// The quadrature's error bound at n = 256: the largest difference from n = 2048 over the IORs, roughnesses
// and angles the tests use is 1.4e-3 for either integral (each integrand is bounded by 1 and piecewise
// smooth, its jumps at the horizon and the critical angle; the worst case is alpha 0.05, where the grid's
// last cells stand for GGX's long tail).
inline constexpr double kAlbedoQuadratureError = 2e-3;

// The albedo floor for an estimate of a rough dielectric or mirror: the lower bound, less the quadrature
// error, less five standard errors of the estimate.
inline double albedo_floor(double eta, double alpha, const Vec3f &wo, const Estimate &e) {
  return ggx_albedo_lower_bound(eta, alpha, wo) - kAlbedoQuadratureError - 5 * e.std_error;
}

// How far an estimate may stand from ggx_albedo_height_correlated: five standard errors and the
// quadrature error.
inline double albedo_tolerance(const Estimate &e) { return 5 * e.std_error + kAlbedoQuadratureError; }

}  // namespace nimbus::test
