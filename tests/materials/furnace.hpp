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

// Single-scattering GGX loses the energy that would scatter between microfacets more than once: at alpha 1
// and normal incidence exactly ln 2 of it. These floors are the smallest albedos this model has over IORs
// {1.0001 .. 4} and both sides, minus 0.05, at alphas {0.05, 0.2, 0.3, 0.5, 0.8, 1} and angles {0, 30,
// 60, 80, 89} from the normal line (theta and 180 - theta share an entry): a broken Jacobian, Fresnel split
// or masking term moves the albedo by more than that. A pair not in the table fails the test.
double albedo_floor(float alpha, float theta_deg);

}  // namespace nimbus::test
