// The building blocks in scattering.hpp: Fresnel, refraction and the GGX distribution, against closed
// forms and numerical integrals.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "chi_square.hpp"
#include "materials/scattering.hpp"
#include "scene/metals.hpp"
#include "test_helpers.hpp"

namespace nimbus::test {
namespace scattering_test {

TEST(Fresnel, DielectricClosedForms) {
  for (float eta : {1.0001f, 1.33f, 1.5f, 2.4f, 4.0f}) {
    const float normal = sqr((eta - 1) / (eta + 1));
    EXPECT_NEAR(fresnel_dielectric(1, eta), normal, 1e-6);
    EXPECT_NEAR(fresnel_dielectric(-1, eta), normal, 1e-6);  // from inside at normal incidence
    EXPECT_NEAR(fresnel_dielectric(1, 1 / eta), normal, 1e-6);
    EXPECT_FLOAT_EQ(fresnel_dielectric(0, eta), 1);  // grazing from outside
    // Total internal reflection beyond the critical angle from inside.
    const float cos_critical = std::sqrt(1 - 1 / (eta * eta));
    EXPECT_EQ(fresnel_dielectric(-0.9f * cos_critical, eta), 1);
    EXPECT_LT(fresnel_dielectric(-std::min(1.0f, 1.1f * cos_critical + 1e-3f), eta), 1);
    // Reflectance is the same from both sides of a refraction (Stokes relations).
    for (float theta_deg : {0.0f, 20.0f, 45.0f, 70.0f, 85.0f}) {
      const Vec3f wi = direction_deg(theta_deg);
      const auto t = refract(wi, Vec3f(0, 0, 1), eta);
      ASSERT_TRUE(t);
      EXPECT_NEAR(fresnel_dielectric(wi.z, eta), fresnel_dielectric(t->wt.z, eta), 1e-5);
      EXPECT_NEAR(fresnel_dielectric(wi.z, eta), fresnel_dielectric(-wi.z, 1 / eta), 1e-6);
    }
  }
  for (float c : {0.0f, 0.3f, 1.0f}) EXPECT_EQ(fresnel_dielectric(c, 1), c == 0 ? 1 : 0);
}

TEST(Fresnel, ConductorMatchesDielectricWithoutAbsorption) {
  for (float eta : {1.33f, 1.5f, 2.4f})
    for (float c : {1.0f, 0.7f, 0.2f, 0.01f})
      EXPECT_NEAR(fresnel_complex(c, eta, 0), fresnel_dielectric(c, eta), 2e-6);
  const MetalIor gold = *find_metal("gold");
  for (float c : {0.0f, 1e-6f, 0.5f, 1.0f}) {
    const Rgb f = fresnel_complex(c, gold.eta, gold.k);
    for (int i = 0; i < 3; ++i) {
      EXPECT_GE(f[i], 0);
      EXPECT_LE(f[i], 1);
    }
  }
  EXPECT_FLOAT_EQ(fresnel_complex(0, 0.2f, 3.9f), 1);
  // Against the complex Fresnel equations in double precision.
  const auto reference = [](double cos_i, double eta, double k) {
    using C = std::complex<double>;
    const C n(eta, k);
    const C cos_t = std::sqrt(1.0 - (1 - cos_i * cos_i) / (n * n));
    const C r_parl = (n * cos_i - cos_t) / (n * cos_i + cos_t),
            r_perp = (cos_i - n * cos_t) / (cos_i + n * cos_t);
    return (std::norm(r_parl) + std::norm(r_perp)) / 2;
  };
  for (const MetalIor &metal : kMetals)
    for (int c = 0; c < 3; ++c)
      for (float cos_i : {1.0f, 0.9f, 0.5f, 0.2f, 0.05f, 1e-3f})
        EXPECT_NEAR(fresnel_complex(cos_i, metal.eta[c], metal.k[c]),
                    reference(cos_i, metal.eta[c], metal.k[c]), 2e-6)
            << metal.name << " channel " << c << " cos " << cos_i;
  // Gold is red-yellow at normal incidence: red reflects most, blue least.
  const Rgb n = fresnel_complex(1, gold.eta, gold.k);
  EXPECT_GT(n.x, n.y);
  EXPECT_GT(n.y, n.z);
  // Degenerate IORs still give a reflectance, not NaN.
  EXPECT_EQ(fresnel_complex(0, 1, 0), 1);
  EXPECT_EQ(fresnel_complex(0.5f, 0, 0), 1);
}

TEST(Refract, SnellAndRoundTrip) {
  for (float eta : {1.0001f, 1.5f, 4.0f, 0.5f})
    for (float theta_deg : {0.0f, 30.0f, 60.0f, 89.0f, 120.0f, 175.0f}) {
      const Vec3f wi = direction_deg(theta_deg);
      const auto t = refract(wi, Vec3f(0, 0, 1), eta);
      const float etap = wi.z > 0 ? eta : 1 / eta;
      if (sin_theta(wi) / etap >= 1) {
        EXPECT_FALSE(t);
        EXPECT_EQ(fresnel_dielectric(wi.z, eta), 1);
        continue;
      }
      ASSERT_TRUE(t);
      EXPECT_EQ(t->etap, etap);
      EXPECT_NEAR(length(t->wt), 1, 1e-5);
      EXPECT_NEAR(sin_theta(t->wt), sin_theta(wi) / etap, 1e-5);
      EXPECT_LT(t->wt.z * wi.z, 0);
      // Refracting back recovers wi (to float accuracy amplified by d(theta_i)/d(theta_t) near grazing).
      const auto back = refract(t->wt, Vec3f(0, 0, 1), eta);
      ASSERT_TRUE(back);
      EXPECT_NEAR(back->wt.x, wi.x, 1e-4);
      EXPECT_NEAR(back->wt.y, wi.y, 1e-4);
      EXPECT_NEAR(back->wt.z, wi.z, 1e-4);
    }
  const Vec3f w = direction_deg(35);
  const Vec3f r = reflect(w, Vec3f(0, 0, 1));
  EXPECT_NEAR(r.x, -w.x, 1e-7);
  EXPECT_NEAR(r.y, -w.y, 1e-7);
  EXPECT_NEAR(r.z, w.z, 1e-7);
}

double integrate_sphere(const DirectionPdf &f) {
  double total = 0;
  const int nt = 32, np = 32;
  for (int i = 0; i < nt; ++i)
    for (int j = 0; j < np; ++j)
      total +=
          integrate_pdf_cell(f, kPi * i / nt, kPi * (i + 1) / nt, 2 * kPi * j / np, 2 * kPi * (j + 1) / np);
  return total;
}

TEST(TrowbridgeReitz, NormalisedProjectedArea) {
  for (float alpha : {0.01f, 0.05f, 0.3f, 1.0f}) {
    const TrowbridgeReitz d(alpha, alpha);
    const double area = integrate_sphere([&](const Vec3f &wm) { return wm.z > 0 ? d.D(wm) * wm.z : 0.0; });
    EXPECT_NEAR(area, 1, 2e-3) << alpha;
  }
  const TrowbridgeReitz aniso(0.1f, 0.4f);
  EXPECT_NEAR(integrate_sphere([&](const Vec3f &wm) { return wm.z > 0 ? aniso.D(wm) * wm.z : 0.0; }), 1,
              2e-3);
}

// The visible-normal density integrates to one from any direction, grazing and below included; this is
// Smith's G1 normalisation.
TEST(TrowbridgeReitz, VisibleNormalsNormalised) {
  for (float alpha : {0.05f, 0.3f, 1.0f})
    for (float theta : {0.0f, 45.0f, 80.0f, 89.9f, 90.0f, 135.0f}) {
      const TrowbridgeReitz d(alpha, alpha);
      const Vec3f w = direction_deg(theta);
      const double total = integrate_sphere([&](const Vec3f &wm) { return wm.z > 0 ? d.D(w, wm) : 0.0; });
      EXPECT_NEAR(total, 1, 3e-3) << "alpha " << alpha << " theta " << theta;
    }
}

TEST(TrowbridgeReitz, MaskingLimits) {
  const TrowbridgeReitz d(0.3f, 0.3f);
  EXPECT_FLOAT_EQ(d.G1(Vec3f(0, 0, 1)), 1);
  EXPECT_EQ(d.G1(Vec3f(1, 0, 0)), 0);
  EXPECT_EQ(d.G(Vec3f(1, 0, 0), Vec3f(0, 0, 1)), 0);
  for (float theta : {10.0f, 50.0f, 85.0f}) {
    const Vec3f a = direction_deg(theta), b = direction_deg(30, 200);
    EXPECT_GT(d.G1(a), 0);
    EXPECT_LE(d.G(a, b), std::min(d.G1(a), d.G1(b)));
    EXPECT_GE(d.G(a, b), d.G1(a) * d.G1(b) - 1e-6f);  // correlated masking shadows less than independent
  }
  // Near-normal precision at the smooth threshold: D peaks at 1 / (pi alpha^2).
  const TrowbridgeReitz sharp(TrowbridgeReitz::kSmoothAlpha, TrowbridgeReitz::kSmoothAlpha);
  EXPECT_FALSE(sharp.effectively_smooth());
  EXPECT_NEAR(sharp.D(Vec3f(0, 0, 1)) * kPi * 1e-8f, 1, 1e-4);
  // Half the peak at tan(theta) = alpha * sqrt(sqrt(2) - 1): resolved although cos(theta) rounds to 1.
  const float t = 1e-4f * std::sqrt(std::sqrt(2.0f) - 1);
  EXPECT_NEAR(sharp.D(normalize(Vec3f(t, 0, 1))) / sharp.D(Vec3f(0, 0, 1)), 0.5, 1e-3);
  EXPECT_TRUE(TrowbridgeReitz(9.9e-5f, 9.9e-5f).effectively_smooth());
}

TEST(TrowbridgeReitz, RoughnessToAlpha) {
  EXPECT_EQ(TrowbridgeReitz::roughness_to_alpha(0), 0);
  EXPECT_FLOAT_EQ(TrowbridgeReitz::roughness_to_alpha(0.5f), 0.25f);
  EXPECT_EQ(TrowbridgeReitz::roughness_to_alpha(1), 1);
  EXPECT_EQ(TrowbridgeReitz::roughness_to_alpha(2), 1);
  EXPECT_EQ(TrowbridgeReitz::roughness_to_alpha(-1), 0);
  EXPECT_EQ(TrowbridgeReitz::roughness_to_alpha(std::nanf("")), 0);
}

}  // namespace scattering_test
}  // namespace nimbus::test
