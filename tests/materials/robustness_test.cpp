// Reciprocity, the delta-lobe conventions, and behaviour at the extremes: IOR 1.0001 and 4, roughness 0
// and 1, exactly grazing wo, wi == wo and wi == -wo. Nothing may return NaN, Inf or a negative value.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include <nimbus/cpp/sampling.hpp>
#include "test_helpers.hpp"

namespace nimbus::test {
namespace robustness_test {

// Relative closeness, with an absolute floor far below any value that could show in an image: at the
// edge of a lobe's support one direction may round to "just valid" and the other to "just invalid".
::testing::AssertionResult close(double a, double b, double rel) {
  if (std::abs(a - b) <= rel * std::max(std::abs(a), std::abs(b)) + 1e-7)
    return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << a << " vs " << b;
}

bool finite_non_negative(const Rgb &f) { return is_finite(f) && f.x >= 0 && f.y >= 0 && f.z >= 0; }
bool finite_non_negative(float x) { return std::isfinite(x) && x >= 0; }

std::vector<NamedBsdf> rough_materials() {
  std::vector<NamedBsdf> m{diffuse_case(Rgb(0.6f))};
  for (float alpha : {1e-3f, 0.05f, 0.3f, 1.0f}) {
    m.push_back(conductor_case(alpha));
    m.push_back(mirror_case(alpha, 0.8f));
    for (float ior : {1.0001f, 1.5f, 4.0f, 0.6f}) m.push_back(dielectric_case(ior, alpha));
  }
  return m;
}

TEST(Reciprocity, ReflectionIsSymmetric) {
  Pcg32 rng(101);
  for (const NamedBsdf &m : rough_materials())
    for (TransportMode mode : {TransportMode::Radiance, TransportMode::Importance})
      for (int i = 0; i < 2000; ++i) {
        Vec3f wo = sample_uniform_sphere(rng.uniform(), rng.uniform());
        Vec3f wi = sample_uniform_sphere(rng.uniform(), rng.uniform());
        if (!same_hemisphere(wo, wi)) wi.z = -wi.z;
        float p_fwd, p_rev, q_fwd, q_rev;
        const Rgb a = m.bsdf.eval(wo, wi, mode, &p_fwd, &p_rev);
        const Rgb b = m.bsdf.eval(wi, wo, mode, &q_fwd, &q_rev);
        // Not bit-exact: Fresnel is evaluated at wo . wm, which rounds differently from wi . wm.
        for (int c = 0; c < 3; ++c) ASSERT_TRUE(close(a[c], b[c], 1e-3)) << m.name;
        ASSERT_TRUE(close(p_fwd, q_rev, 1e-3)) << m.name;
        ASSERT_TRUE(close(p_rev, q_fwd, 1e-3)) << m.name;
      }
}

// Importance transport is the adjoint of radiance transport: f_radiance(wo, wi) = f_importance(wi, wo).
TEST(Reciprocity, TransmissionIsAdjoint) {
  Pcg32 rng(103);
  for (const NamedBsdf &m : rough_materials()) {
    if (m.ior == 0) continue;
    // The two directions build the half vector as etap wi + wo and wo / etap + wi, rounded differently;
    // as in consistency_test.cpp the difference in D is ~2e-7 / (alpha |etap wi + wo|), large near IOR 1.
    int nonzero = 0;
    for (int i = 0; i < 4000; ++i) {
      const Vec3f wo = sample_uniform_sphere(rng.uniform(), rng.uniform());
      Vec3f wi = sample_uniform_sphere(rng.uniform(), rng.uniform());
      if (same_hemisphere(wo, wi)) wi.z = -wi.z;
      const float etap = wo.z > 0 ? m.ior : 1 / m.ior;
      const double tol = 1e-3 + 10 * 2e-7 / (m.bsdf.min_alpha() * length(wi * etap + wo));
      const float rad = m.bsdf.eval(wo, wi, TransportMode::Radiance).x;
      const float imp = m.bsdf.eval(wi, wo, TransportMode::Importance).x;
      ASSERT_TRUE(close(rad, imp, tol)) << m.name;
      nonzero += rad > 0;
    }
    if (std::abs(m.ior - 1) > 1e-3f && m.bsdf.min_alpha() >= 0.05f) {
      EXPECT_GT(nonzero, 100) << m.name;
    }
  }
}

TEST(Delta, EvalAndPdfAreZero) {
  std::vector<NamedBsdf> smooth{conductor_case(0), mirror_case(0), conductor_case(5e-5f)};
  for (float ior : {1.0f, 1.0001f, 1.5f, 4.0f, 0.5f}) smooth.push_back(dielectric_case(ior, 0));
  smooth.push_back(dielectric_case(1.0f, 0.5f));  // index-matched: a pass-through however rough
  Pcg32 rng(107);
  for (const NamedBsdf &m : smooth) {
    ASSERT_TRUE(m.delta) << m.name;
    EXPECT_EQ(m.bsdf.min_alpha(), 0) << m.name;
    EXPECT_NE(m.bsdf.lobes() & NIMBUS_LOBE_SPECULAR, 0u) << m.name;
    EXPECT_EQ(m.bsdf.lobes() & (NIMBUS_LOBE_GLOSSY | NIMBUS_LOBE_DIFFUSE), 0u) << m.name;
    for (int i = 0; i < 500; ++i) {
      const Vec3f wo = sample_uniform_sphere(rng.uniform(), rng.uniform());
      const BsdfSample s = m.bsdf.sample(wo, rng.uniform(), rng.uniform2(), TransportMode::Radiance);
      // The exact delta direction, its mirror images, and a random direction all evaluate to zero.
      for (const Vec3f &wi : {s.wi, mirror_z(wo), -wo, sample_uniform_sphere(rng.uniform(), rng.uniform())}) {
        float p_fwd = -1, p_rev = -1;
        EXPECT_TRUE(is_black(m.bsdf.eval(wo, wi, TransportMode::Radiance, &p_fwd, &p_rev))) << m.name;
        EXPECT_EQ(p_fwd, 0);
        EXPECT_EQ(p_rev, 0);
        EXPECT_EQ(m.bsdf.pdf(wo, wi, TransportMode::Importance), 0) << m.name;
      }
    }
  }
}

// Delta samples: pdf = pdf_rev = 1, f = weight / |cos wi|, the exact mirror or Snell direction.
TEST(Delta, SamplesFollowTheAbiConvention) {
  const Vec3f wo = direction_deg(40);
  const Rgb gold_fresnel = conductor_case(0).bsdf.albedo(wo);
  const BsdfSample g = conductor_case(0).bsdf.sample(wo, 0.3f, {0.2f, 0.7f}, TransportMode::Radiance);
  EXPECT_EQ(g.wi, mirror_z(wo));
  EXPECT_EQ(g.pdf, 1);
  EXPECT_EQ(g.pdf_rev, 1);
  EXPECT_EQ(g.lobe, NIMBUS_LOBE_REFLECTION | NIMBUS_LOBE_SPECULAR);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(g.f[c] * abs_cos_theta(g.wi), gold_fresnel[c], 1e-6);

  const BsdfSample mr = mirror_case(0, 0.7f).bsdf.sample(wo, 0.9f, {0.9f, 0.1f}, TransportMode::Importance);
  EXPECT_NEAR(mr.f.x * abs_cos_theta(mr.wi), 0.7f, 1e-6);

  for (float ior : {1.33f, 4.0f})
    for (float theta : {40.0f, 170.0f}) {
      const Vec3f w = direction_deg(theta);
      const Bsdf glass = DielectricBsdf(ior, 0);
      const float r = fresnel_dielectric(w.z, ior);
      const BsdfSample refl = glass.sample(w, r * 0.999f, {0.5f, 0.5f}, TransportMode::Radiance);
      EXPECT_EQ(refl.lobe, NIMBUS_LOBE_REFLECTION | NIMBUS_LOBE_SPECULAR);
      EXPECT_EQ(refl.wi, mirror_z(w));
      EXPECT_NEAR(refl.f.x * abs_cos_theta(refl.wi), 1, 1e-6);
      const BsdfSample refr =
          glass.sample(w, std::min(r * 1.001f + 1e-6f, 0.9999f), {0.5f, 0.5f}, TransportMode::Radiance);
      EXPECT_EQ(refr.lobe, NIMBUS_LOBE_TRANSMISSION | NIMBUS_LOBE_SPECULAR);
      const float etap = w.z > 0 ? ior : 1 / ior;
      EXPECT_EQ(refr.eta, etap);
      EXPECT_EQ(refr.pdf, 1);
      EXPECT_EQ(refr.pdf_rev, 1);
      // Snell: sin(theta_t) = sin(theta_i) / etap, on the other side, in the plane of incidence.
      EXPECT_NEAR(sin_theta(refr.wi), sin_theta(w) / etap, 1e-5);
      EXPECT_LT(refr.wi.z * w.z, 0);
      EXPECT_NEAR(refr.wi.x * w.y - refr.wi.y * w.x, 0, 1e-6);
      EXPECT_NEAR(refr.f.x * abs_cos_theta(refr.wi), 1 / (etap * etap), 1e-5);
    }

  const BsdfSample pass = DielectricBsdf(1.0f, 0.7f).sample(wo, 0.1f, {0.3f, 0.3f}, TransportMode::Radiance);
  EXPECT_EQ(pass.wi, -wo);
  EXPECT_EQ(pass.lobe, NIMBUS_LOBE_TRANSMISSION | NIMBUS_LOBE_SPECULAR);
  EXPECT_NEAR(pass.f.x * abs_cos_theta(pass.wi), 1, 1e-6);
}

TEST(Extremes, NoNanInfOrNegative) {
  const float tiny = 1e-7f, tinier = 1e-30f;
  std::vector<Vec3f> wos{{0, 0, 1},
                         {0, 0, -1},
                         {1, 0, 0},
                         {0.6f, -0.8f, 0},
                         {0, 1, tinier},
                         {std::sqrt(1 - tiny * tiny), 0, tiny},
                         {std::sqrt(1 - tiny * tiny), 0, -tiny},
                         {1, 0, tinier},
                         {1, 0, -tinier},
                         {1, 0, -0.0f}};
  for (float theta : {30.0f, 89.99f, 90.01f, 150.0f}) wos.push_back(direction_deg(theta));
  Pcg32 rng(109);
  int checks = 0;
  for (const NamedBsdf &m : extreme_catalogue())
    for (const Vec3f &wo : wos)
      for (TransportMode mode : {TransportMode::Radiance, TransportMode::Importance}) {
        SCOPED_TRACE(m.name + " wo (" + std::to_string(wo.x) + ", " + std::to_string(wo.y) + ", " +
                     std::to_string(wo.z) + ")");
        std::vector<Vec3f> wis{wo,        -wo,       mirror_z(wo), -mirror_z(wo),
                               {1, 0, 0}, {0, 1, 0}, {0, 0, 1},    {0, 0, -1}};
        for (int i = 0; i < 16; ++i) wis.push_back(sample_uniform_sphere(rng.uniform(), rng.uniform()));
        for (const Vec3f &wi : wis) {
          float p_fwd = -1, p_rev = -1;
          const Rgb f = m.bsdf.eval(wo, wi, mode, &p_fwd, &p_rev);
          ASSERT_TRUE(finite_non_negative(f));
          ASSERT_TRUE(finite_non_negative(p_fwd));
          ASSERT_TRUE(finite_non_negative(p_rev));
          ASSERT_TRUE(finite_non_negative(m.bsdf.pdf(wo, wi, mode)));
          // The null-pointer form must work too.
          ASSERT_TRUE(finite_non_negative(m.bsdf.eval(wo, wi, mode)));
          ++checks;
        }
        std::vector<std::pair<float, Vec2f>> us;
        for (float a : {0.0f, 0.5f, 0x1.fffffep-1f})
          for (float b : {0.0f, 0.25f, 0x1.fffffep-1f})
            us.push_back({a, Vec2f{b, a}}), us.push_back({b, Vec2f{a, b}});
        for (int i = 0; i < 64; ++i) us.push_back({rng.uniform(), rng.uniform2()});
        for (const auto &[uc, u] : us) {
          const BsdfSample s = m.bsdf.sample(wo, uc, u, mode);
          ASSERT_TRUE(finite_non_negative(s.pdf));
          if (s.pdf == 0) {
            EXPECT_EQ(s.lobe, 0u);
            continue;
          }
          ASSERT_TRUE(finite_non_negative(s.f));
          ASSERT_TRUE(finite_non_negative(s.pdf_rev));
          ASSERT_TRUE(std::isfinite(s.eta) && s.eta > 0);
          ASSERT_NEAR(length(s.wi), 1, 1e-3);
          ASSERT_NE(s.lobe, 0u);
          // A grazing wo scatters nowhere: eval() is zero for it, so sample() must fail too.
          ASSERT_NE(wo.z, 0);
          ++checks;
        }
      }
  EXPECT_GT(checks, 10000);
}

TEST(Lobes, DescribeEachMaterial) {
  EXPECT_EQ(Bsdf(DiffuseBsdf(Rgb(0.5f))).lobes(), NIMBUS_LOBE_REFLECTION | NIMBUS_LOBE_DIFFUSE);
  EXPECT_EQ(Bsdf(DiffuseBsdf(Rgb(0.5f))).min_alpha(), 1);
  EXPECT_EQ(conductor_case(0).bsdf.lobes(), NIMBUS_LOBE_REFLECTION | NIMBUS_LOBE_SPECULAR);
  EXPECT_EQ(conductor_case(0.3f).bsdf.lobes(), NIMBUS_LOBE_REFLECTION | NIMBUS_LOBE_GLOSSY);
  EXPECT_FLOAT_EQ(conductor_case(0.3f).bsdf.min_alpha(), 0.3f);
  EXPECT_EQ(conductor_case(9.9e-5f).bsdf.min_alpha(), 0);  // below the smooth threshold
  EXPECT_FLOAT_EQ(conductor_case(1e-4f).bsdf.min_alpha(), 1e-4f);
  EXPECT_EQ(dielectric_case(1.5f, 0).bsdf.lobes(),
            NIMBUS_LOBE_REFLECTION | NIMBUS_LOBE_TRANSMISSION | NIMBUS_LOBE_SPECULAR);
  EXPECT_EQ(dielectric_case(1.5f, 0.2f).bsdf.lobes(),
            NIMBUS_LOBE_REFLECTION | NIMBUS_LOBE_TRANSMISSION | NIMBUS_LOBE_GLOSSY);
  EXPECT_FLOAT_EQ(dielectric_case(1.5f, 0.2f).bsdf.min_alpha(), 0.2f);
  EXPECT_EQ(dielectric_case(1.0f, 0.2f).bsdf.lobes(), NIMBUS_LOBE_TRANSMISSION | NIMBUS_LOBE_SPECULAR);
  EXPECT_EQ(dielectric_case(1.0f, 0.2f).bsdf.min_alpha(), 0);
}

}  // namespace robustness_test
}  // namespace nimbus::test
