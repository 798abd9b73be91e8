// sample() must agree with eval() and pdf() at the direction it returns: same weight f |cos| / pdf, same
// pdf, and a reverse pdf equal to pdf(wi -> wo). Delta samples must follow the ABI's delta convention.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "test_helpers.hpp"

namespace nimbus::test {
namespace consistency_test {

constexpr float kAngles[] = {0, 10, 30, 60, 80, 89, 89.9f, 180, 150, 120, 100, 91, 90.1f};

// |a - b| small relative to the larger, with an absolute floor for values near zero.
::testing::AssertionResult close(double a, double b, double rel, double abs_floor = 1e-6) {
  if (std::abs(a - b) <= rel * std::max(std::abs(a), std::abs(b)) + abs_floor)
    return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << a << " vs " << b << " (rel " << std::abs(a - b) / std::abs(b) << ")";
}

std::vector<NamedBsdf> materials() {
  std::vector<NamedBsdf> m = extreme_catalogue();
  for (float alpha : {0.2f, 0.5f}) {
    m.push_back(conductor_case(alpha));
    for (float ior : {1.5f, 2.4f}) m.push_back(dielectric_case(ior, alpha));
  }
  m.push_back(mirror_case(0.3f, 0.6f));
  return m;
}

class SampleConsistency : public ::testing::TestWithParam<NamedBsdf> {};

TEST_P(SampleConsistency, MatchesEvalAndPdf) {
  const NamedBsdf &m = GetParam();
  // eval() rebuilds the half vector from (wo, wi); sample() knows the exact one. The rebuild divides the
  // float rounding of wi (~1e-7) by the length of the unnormalised half vector etap wi + wo, and D turns
  // an angular error into a relative one of up to ~2 / alpha per radian. For alpha ~1e-3 at grazing angles,
  // or near IOR 1 (wi ~ -wo, the sum cancels), f and pdf separately are therefore only reproducible to that
  // conditioning. Their ratio, the weight, does not depend on wm's exact position and is checked tightly.
  const bool dielectric = m.ior > 0;
  const double alpha = m.bsdf.min_alpha();
  const auto value_tol = [&](const Vec3f &wo, const BsdfSample &s) {
    const double h = length(s.wi * s.eta + wo);
    return 2e-3 + 10 * 2e-7 / (alpha * h);  // a tenfold margin over that estimate
  };
  Pcg32 rng(42);
  int valid = 0;
  for (float theta : kAngles)
    for (TransportMode mode : {TransportMode::Radiance, TransportMode::Importance})
      for (int i = 0; i < 500; ++i) {
        const Vec3f wo = direction_deg(theta, 17 + 3 * i);
        const BsdfSample s = m.bsdf.sample(wo, rng.uniform(), rng.uniform2(), mode);
        if (s.pdf == 0) continue;
        ++valid;
        SCOPED_TRACE(m.name + " theta " + std::to_string(theta) + " sample " + std::to_string(i));
        ASSERT_TRUE(close(length(s.wi), 1, 1e-4));
        ASSERT_EQ(s.lobe & ~m.bsdf.lobes(), 0u) << "sampled lobe not in lobes()";
        const bool reflected = same_hemisphere(wo, s.wi);
        ASSERT_EQ((s.lobe & NIMBUS_LOBE_REFLECTION) != 0, reflected);
        ASSERT_EQ((s.lobe & NIMBUS_LOBE_TRANSMISSION) != 0, !reflected);
        if (!reflected && dielectric) {
          ASSERT_FLOAT_EQ(s.eta, wo.z > 0 ? m.ior : 1 / m.ior);
        } else {
          ASSERT_EQ(s.eta, 1);
        }
        float pdf_fwd = -1, pdf_rev = -1;
        const Rgb f = m.bsdf.eval(wo, s.wi, mode, &pdf_fwd, &pdf_rev);
        if (m.delta) {
          ASSERT_NE(s.lobe & NIMBUS_LOBE_SPECULAR, 0u);
          ASSERT_EQ(s.pdf, 1);
          ASSERT_EQ(s.pdf_rev, 1);
          ASSERT_TRUE(is_black(f));
          ASSERT_EQ(pdf_fwd, 0);
          ASSERT_EQ(pdf_rev, 0);
          continue;
        }
        ASSERT_EQ(s.lobe & NIMBUS_LOBE_SPECULAR, 0u);
        ASSERT_GT(pdf_fwd, 0);
        const float cos_i = abs_cos_theta(s.wi);
        const double tol = value_tol(wo, s);
        for (int c = 0; c < 3; ++c) {
          ASSERT_TRUE(close(s.f[c] * cos_i / s.pdf, f[c] * cos_i / pdf_fwd, 1e-3)) << "weight, channel " << c;
          ASSERT_TRUE(close(s.f[c], f[c], tol)) << "f, channel " << c;
        }
        ASSERT_TRUE(close(s.pdf, pdf_fwd, tol));
        ASSERT_TRUE(close(s.pdf, m.bsdf.pdf(wo, s.wi, mode), tol));
        const float pdf_back = m.bsdf.pdf(s.wi, wo, mode);
        ASSERT_TRUE(close(s.pdf_rev, pdf_back, tol)) << "pdf_rev vs pdf(wi -> wo)";
        ASSERT_TRUE(close(pdf_rev, pdf_back, tol)) << "eval's pdf_rev vs pdf(wi -> wo)";
      }
  // Every material but the black-hole cases must produce samples at most angles.
  EXPECT_GT(valid, 1000);
}

INSTANTIATE_TEST_SUITE_P(All, SampleConsistency, ::testing::ValuesIn(materials()),
                         [](const auto &info) { return sanitize_name(info.param.name); });

}  // namespace consistency_test
}  // namespace nimbus::test
