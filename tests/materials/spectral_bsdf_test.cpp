// Materials at one wavelength (materials/spectral_bsdf.hpp): a dispersive glass refracts by Snell's law
// with its index at lambda, reflects (n-1)^2/(n+1)^2 at normal incidence, and its rough form passes the
// furnace, eval/sample and chi-square checks the RGB dielectric passes, at wavelengths across the range;
// every other material's value is the uplift of its RGB value; and the RGB BSDF of a dispersive glass is
// the plain dielectric at n_d, bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "chi_square.hpp"
#include "core/rgb_uplift_table.hpp"
#include "furnace.hpp"
#include "materials/spectral_bsdf.hpp"
#include "scene/scene_desc.hpp"
#include "test_helpers.hpp"

namespace nimbus::test {
namespace spectral_bsdf_test {

// A dense flint (n_d 1.8, V_d 25): n runs from 1.852 at 400 nm to 1.786 at 700 nm, ten times the spread
// the tolerances below resolve, so a glass that ignored lambda fails.
const IorCurve kFlint = IorCurve::abbe(1.8, 25);
constexpr float kLambdas[] = {400, float(kFraunhoferF), 550, float(kFraunhoferC), 700};

SpectralBsdf flint_at(float lambda, float alpha) {
  return SpectralBsdf(DielectricBsdf::dispersive(1.8f, alpha), &kFlint, lambda);
}

TEST(SpectralDielectric, RefractsBySnellsLawWithTheIndexAtLambda) {
  std::vector<float> angles;  // refracted at 40 degrees, by lambda
  for (float lambda : kLambdas) {
    const SpectralBsdf glass = flint_at(lambda, 0);
    const float n = kFlint.at(lambda);
    for (float theta : {10.0f, 40.0f, 75.0f, 170.0f, 150.0f}) {
      const Vec3f wo = direction_deg(theta);
      // uc just below 1 picks refraction whenever Fresnel leaves any transmission.
      const BsdfSample s = glass.sample(wo, 0.9999f, {0.5f, 0.5f}, TransportMode::Radiance);
      const std::string where = "lambda " + std::to_string(lambda) + " theta " + std::to_string(theta);
      ASSERT_GT(s.pdf, 0) << where;
      ASSERT_TRUE(s.lobe & NIMBUS_LOBE_TRANSMISSION) << where;
      const bool entering = wo.z > 0;
      const float n_o = entering ? 1 : n, n_i = entering ? n : 1;
      const float sin_o = std::sqrt(std::max(0.0f, 1 - wo.z * wo.z));
      const float sin_i = std::sqrt(std::max(0.0f, 1 - s.wi.z * s.wi.z));
      // float directions: sines to a few ulps of 1, relative to the larger side.
      EXPECT_NEAR(n_o * sin_o, n_i * sin_i, 2e-6f * n) << where;
      EXPECT_LT(s.wi.z * wo.z, 0) << where;
      // In the plane of incidence, on the far side of the normal.
      EXPECT_NEAR(s.wi.x * wo.y - s.wi.y * wo.x, 0, 1e-6f) << where;
      EXPECT_LE(s.wi.x * wo.x + s.wi.y * wo.y, 0) << where;
      EXPECT_FLOAT_EQ(s.eta, entering ? n : 1 / n) << where;
      if (theta == 40.0f) angles.push_back(std::acos(-s.wi.z));
    }
  }
  // Red bends less: the refracted angle grows with lambda as n falls, by 0.8 degrees from 400 to 700 nm.
  for (size_t i = 1; i < angles.size(); ++i) EXPECT_GT(angles[i], angles[i - 1]) << i;
  EXPECT_GT(angles.back() - angles.front(), 0.01f);
}

TEST(SpectralDielectric, NormalIncidenceReflectsTheFresnelOfTheIndexAtLambda) {
  for (float lambda : kLambdas) {
    const SpectralBsdf glass = flint_at(lambda, 0);
    const double n = kFlint.index(lambda), r = (n - 1) * (n - 1) / ((n + 1) * (n + 1));
    const Vec3f wo(0, 0, 1);
    // The smooth dielectric reflects exactly when uc < R: the threshold is R itself (float rounding of R
    // and of the Fresnel formula, 1e-6).
    const float below = float(r) - 1e-6f, above = float(r) + 1e-6f;
    EXPECT_TRUE(glass.sample(wo, below, {0, 0}, TransportMode::Radiance).lobe & NIMBUS_LOBE_REFLECTION);
    EXPECT_TRUE(glass.sample(wo, above, {0, 0}, TransportMode::Radiance).lobe & NIMBUS_LOBE_TRANSMISSION);
    // And by counting: the reflected share of 400k samples is binomial, 5 sigma wide (about 1.5e-3, a
    // fifth of R's change from 400 to 700 nm).
    Pcg32 rng(seed_from("fresnel" + std::to_string(lambda)));
    const int count = 400000;
    int reflected = 0;
    for (int i = 0; i < count; ++i)
      reflected += glass.sample(wo, rng.uniform(), rng.uniform2(), TransportMode::Radiance).wi.z > 0;
    EXPECT_NEAR(double(reflected) / count, r, 5 * std::sqrt(r * (1 - r) / count)) << lambda;
  }
}

// The rough glass at lambda, through the same estimators as the RGB dielectric's furnace tests.
TEST(SpectralDielectric, RoughGlassPassesTheFurnaceAtEveryLambda) {
  for (float lambda : kLambdas)
    for (float alpha : {0.05f, 0.3f, 0.8f})
      for (float theta : {0.0f, 30.0f, 60.0f, 80.0f, 180.0f, 150.0f, 120.0f, 100.0f}) {
        const SpectralBsdf glass = flint_at(lambda, alpha);
        const Vec3f wo = direction_deg(theta);
        const Estimate e = albedo_by_sampling(glass, wo, TransportMode::Importance, 40000, 13);
        const std::string where = "lambda " + std::to_string(lambda) + " alpha " + std::to_string(alpha) +
                                  " theta " + std::to_string(theta) + ": " + std::to_string(e.mean);
        EXPECT_LE(e.mean, 1 + 5 * e.std_error + 1e-5) << where;
        EXPECT_GE(e.mean, albedo_floor(kFlint.at(lambda), alpha, wo, e)) << where;
        EXPECT_NEAR(e.mean, ggx_albedo_height_correlated(kFlint.at(lambda), alpha, wo), albedo_tolerance(e))
            << where;
        // eval's normalisation against the sampler's, both modes: 5 combined standard errors.
        for (TransportMode mode : {TransportMode::Radiance, TransportMode::Importance}) {
          const Estimate a = albedo_by_sampling(glass, wo, mode, 40000, 19);
          const Estimate b = albedo_by_eval(glass, wo, mode, 150000, 23);
          EXPECT_NEAR(a.mean, b.mean, 5 * std::hypot(a.std_error, b.std_error) + 1e-4) << where;
        }
      }
}

TEST(SpectralDielectric, RoughGlassSamplesItsPdfAtEveryLambda) {
  const float alphas[] = {0.05f, 0.3f}, thetas[] = {0.0f, 60.0f, 140.0f};
  // One family-wise significance of 1% over these tests (Sidak), as the RGB chi-square tests have.
  const double significance =
      sidak_significance(0.01, std::size(kLambdas) * std::size(alphas) * std::size(thetas));
  for (float lambda : kLambdas)
    for (float alpha : alphas)
      for (float theta : thetas) {
        const SpectralBsdf glass = flint_at(lambda, alpha);
        const Vec3f wo = direction_deg(theta);
        ChiSquareConfig config;
        config.seed =
            seed_from("chi2 " + std::to_string(lambda) + std::to_string(alpha) + std::to_string(theta));
        const ChiSquareResult r = chi_square_test(
            [&](Pcg32 &rng) -> std::optional<Vec3f> {
              const float uc = rng.uniform();
              const BsdfSample s = glass.sample(wo, uc, rng.uniform2(), TransportMode::Radiance);
              if (s.pdf == 0) return std::nullopt;
              return s.wi;
            },
            [&](const Vec3f &wi) { return double(glass.pdf(wo, wi, TransportMode::Radiance)); }, config);
        const std::string where = "lambda " + std::to_string(lambda) + " alpha " + std::to_string(alpha) +
                                  " theta " + std::to_string(theta) + ": " + r.describe();
        EXPECT_TRUE(r.error.empty()) << where;
        EXPECT_GE(r.p_value, significance) << where;
      }
}

// Without a curve the glass keeps its one index: the values at lambda are the RGB values, exactly.
TEST(SpectralMaterials, NonDispersiveGlassIsItsRgbSelf) {
  for (float alpha : {0.0f, 0.3f}) {
    const Bsdf rgb = DielectricBsdf(1.5f, alpha);
    const SpectralBsdf at = SpectralBsdf(rgb, nullptr, 480);
    Pcg32 rng(7);
    for (int i = 0; i < 2000; ++i) {
      const Vec3f wo = direction_deg(180 * rng.uniform(), 360 * rng.uniform());
      const Vec3f wi = direction_deg(180 * rng.uniform(), 360 * rng.uniform());
      float p0 = 0, p1 = 0;
      ASSERT_EQ(at.eval(wo, wi, TransportMode::Radiance, &p0),
                rgb.eval(wo, wi, TransportMode::Radiance, &p1).x);
      ASSERT_EQ(p0, p1);
      const float uc = rng.uniform();
      const Vec2f u = rng.uniform2();
      const BsdfSample a = at.sample(wo, uc, u, TransportMode::Importance);
      const BsdfSample b = rgb.sample(wo, uc, u, TransportMode::Importance);
      ASSERT_EQ(a.wi, b.wi);
      ASSERT_EQ(a.f, b.f);
      ASSERT_EQ(a.pdf, b.pdf);
    }
  }
}

// Diffuse: uplift(albedo) / pi. Metals: the uplift of the RGB value (the Fresnel colour times the
// microfacet terms), so a dispersive render keeps their colours. Directions and pdfs are the RGB ones.
TEST(SpectralMaterials, OtherMaterialsUpliftTheirRgbValue) {
  const Rgb albedo(0.7f, 0.3f, 0.1f);
  const std::vector<NamedBsdf> cases{diffuse_case(albedo),
                                     conductor_case(0.3f),
                                     conductor_case(0),
                                     {"red mirror", ConductorBsdf::mirror(Rgb(0.9f, 0.2f, 0.2f), 0.2f)}};
  for (const NamedBsdf &m : cases)
    for (float lambda : kLambdas) {
      const SpectralBsdf at(m.bsdf, nullptr, lambda);
      Pcg32 rng(seed_from(m.name));
      for (int i = 0; i < 500; ++i) {
        const Vec3f wo = direction_deg(89 * rng.uniform(), 360 * rng.uniform());
        const Vec3f wi = direction_deg(89 * rng.uniform(), 360 * rng.uniform());
        float p_spectral = 0, p_rgb = 0;
        const float f = at.eval(wo, wi, TransportMode::Radiance, &p_spectral);
        const Rgb f_rgb = m.bsdf.eval(wo, wi, TransportMode::Radiance, &p_rgb);
        // One uplift of the same RGB: equal to float rounding.
        EXPECT_NEAR(f, uplift(f_rgb, lambda), 1e-6f * std::max(1.0f, f)) << m.name;
        EXPECT_EQ(p_spectral, p_rgb) << m.name;
        const float uc = rng.uniform();
        const Vec2f u = rng.uniform2();
        const BsdfSample s = at.sample(wo, uc, u, TransportMode::Radiance);
        const BsdfSample r = m.bsdf.sample(wo, uc, u, TransportMode::Radiance);
        ASSERT_EQ(s.wi, r.wi) << m.name;
        ASSERT_EQ(s.pdf, r.pdf) << m.name;
        if (s.pdf > 0) EXPECT_NEAR(s.f.x, uplift(r.f, lambda), 1e-6f * std::max(1.0f, s.f.x)) << m.name;
        EXPECT_EQ(s.f.x, s.f.y);
        EXPECT_EQ(s.f.x, s.f.z);
      }
      if (m.name.rfind("diffuse", 0) == 0) {
        // The diffuse value is uplift(albedo) / pi: homogeneity, to a few float roundings.
        const float f = at.eval(Vec3f(0, 0, 1), direction_deg(30), TransportMode::Radiance);
        const float expected = uplift(albedo, lambda) * kInvPi;
        EXPECT_NEAR(f, expected, 1e-5f * expected) << lambda;
        // And not a constant: a red-brown albedo reflects more at 700 nm than at 400 nm.
        EXPECT_GT(uplift(albedo, 700), 2 * uplift(albedo, 400));
      }
    }
}

TEST(SpectralMaterials, WavelengthsOutsideTheVisibleRangeScatterNothing) {
  for (float lambda : {300.0f, 900.0f, std::nanf("")}) {
    const SpectralBsdf at(DiffuseBsdf(Rgb(0.5f)), nullptr, lambda);
    float p = 1;
    EXPECT_EQ(at.eval(Vec3f(0, 0, 1), Vec3f(0, 0, 1), TransportMode::Radiance, &p), 0);
    EXPECT_EQ(p, 0);
    EXPECT_EQ(at.sample(Vec3f(0, 0, 1), 0.5f, {0.5f, 0.5f}, TransportMode::Radiance).pdf, 0);
    EXPECT_EQ(flint_at(lambda, 0).sample(Vec3f(0, 0, 1), 0.5f, {0.5f, 0.5f}, TransportMode::Radiance).pdf, 0);
  }
}

// The RGB entry points of a dispersive glass are the plain dielectric at n_d: same numbers, bit for bit,
// and only the lobe bit that announces the dispersion differs.
TEST(SpectralMaterials, RgbBsdfOfADispersiveGlassIsTheConstantOne) {
  for (float roughness : {0.0f, 0.5f}) {
    MaterialDesc dispersive, constant;
    dispersive.type = constant.type = MaterialType::Dielectric;
    dispersive.roughness = constant.roughness = roughness;
    dispersive.dispersion = kFlint;
    dispersive.ior = constant.ior = 1.8f;
    const Bsdf a = make_bsdf(dispersive), b = make_bsdf(constant);
    EXPECT_EQ(a.lobes(), b.lobes() | NIMBUS_LOBE_DISPERSIVE);
    EXPECT_EQ(b.lobes() & NIMBUS_LOBE_DISPERSIVE, 0u);
    Pcg32 rng(11);
    for (int i = 0; i < 5000; ++i) {
      const Vec3f wo = direction_deg(180 * rng.uniform(), 360 * rng.uniform());
      const Vec3f wi = direction_deg(180 * rng.uniform(), 360 * rng.uniform());
      for (TransportMode mode : {TransportMode::Radiance, TransportMode::Importance}) {
        float pa = 0, pb = 0, ra = 0, rb = 0;
        ASSERT_EQ(a.eval(wo, wi, mode, &pa, &ra), b.eval(wo, wi, mode, &pb, &rb));
        ASSERT_EQ(pa, pb);
        ASSERT_EQ(ra, rb);
        ASSERT_EQ(a.pdf(wo, wi, mode), b.pdf(wo, wi, mode));
        const float uc = rng.uniform();
        const Vec2f u = rng.uniform2();
        const BsdfSample sa = a.sample(wo, uc, u, mode), sb = b.sample(wo, uc, u, mode);
        ASSERT_EQ(sa.wi, sb.wi);
        ASSERT_EQ(sa.f, sb.f);
        ASSERT_EQ(sa.pdf, sb.pdf);
        ASSERT_EQ(sa.pdf_rev, sb.pdf_rev);
        ASSERT_EQ(sa.eta, sb.eta);
        ASSERT_EQ(sa.lobe, sb.lobe);
      }
    }
  }
}

}  // namespace spectral_bsdf_test
}  // namespace nimbus::test
