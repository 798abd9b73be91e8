// Goodness of fit of every non-delta BSDF's sample() against its pdf(), over incident angles from normal
// to grazing and from both sides of the surface.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include <nimbus/cpp/sampling.hpp>
#include "chi_square.hpp"
#include "test_helpers.hpp"

namespace nimbus::test {
namespace chi_square_test_file {

struct Chi2Case {
  NamedBsdf material;
  float theta_deg;  // of wo; > 90 = below the surface
  std::string name() const {
    return sanitize_name(material.name + "_theta" + std::to_string(static_cast<int>(theta_deg * 10)));
  }
};

std::vector<Chi2Case> diffuse_cases() {
  std::vector<Chi2Case> c;
  for (float theta : {0.0f, 60.0f, 89.0f, 135.0f}) c.push_back({diffuse_case(Rgb(0.7f)), theta});
  return c;
}

std::vector<Chi2Case> conductor_cases() {
  std::vector<Chi2Case> c;
  for (float alpha : {0.05f, 0.2f, 0.5f, 1.0f})
    for (float theta : {0.0f, 30.0f, 60.0f, 80.0f, 89.0f, 120.0f})
      c.push_back({conductor_case(alpha), theta});
  // The ideal mirror shares the sampler but not the Fresnel term.
  c.push_back({mirror_case(0.3f, 0.9f), 45.0f});
  return c;
}

// IOR 1.0001 is left out: its transmission lobe is ~1e-4 rad wide, a delta to any histogram; the energy and
// robustness tests cover it.
std::vector<Chi2Case> dielectric_cases() {
  std::vector<Chi2Case> c;
  for (float ior : {1.33f, 1.5f, 2.4f, 4.0f})
    for (float alpha : {0.05f, 0.3f, 0.8f})
      // From outside: normal, oblique, grazing. From inside: normal, 40 degrees (just below the critical
      // angle of IOR 1.5, beyond those of 2.4 and 4), grazing.
      for (float theta : {0.0f, 60.0f, 88.0f, 180.0f, 140.0f, 92.0f})
        c.push_back({dielectric_case(ior, alpha), theta});
  return c;
}

// All chi-square tests in this binary share one family-wise significance level of 1%.
const int kTestCount =
    static_cast<int>(diffuse_cases().size() + conductor_cases().size() + dielectric_cases().size()) + 1;
const double kSignificance = sidak_significance(0.01, kTestCount);

ChiSquareResult bsdf_chi_square(const Bsdf &bsdf, const Vec3f &wo, uint64_t seed, double pdf_scale = 1,
                                float skew = 1) {
  ChiSquareConfig config;
  config.seed = seed;
  // The pdf does not depend on the transport mode; radiance is as good as importance here.
  const TransportMode mode = TransportMode::Radiance;
  const DirectionSampler sampler = [&](Pcg32 &rng) -> std::optional<Vec3f> {
    const float uc = rng.uniform();
    Vec2f u = rng.uniform2();
    u.x = std::pow(u.x, skew);
    const BsdfSample s = bsdf.sample(wo, uc, u, mode);
    if (s.pdf == 0) return std::nullopt;
    return s.wi;
  };
  const DirectionPdf pdf = [&](const Vec3f &wi) { return pdf_scale * bsdf.pdf(wo, wi, mode); };
  return chi_square_test(sampler, pdf, config);
}

class ChiSquare : public ::testing::TestWithParam<Chi2Case> {};

TEST_P(ChiSquare, SampleMatchesPdf) {
  const Chi2Case &c = GetParam();
  ASSERT_FALSE(c.material.delta);
  const Vec3f wo = direction_deg(c.theta_deg);
  const ChiSquareResult r = bsdf_chi_square(c.material.bsdf, wo, seed_from(c.name()));
  EXPECT_TRUE(r.error.empty()) << r.describe();
  EXPECT_GE(r.p_value, kSignificance) << r.describe();
  // The pdf's mass plus the failed samples' share account for every sample.
  EXPECT_LE(r.pdf_integral, 1 + 1e-3) << r.describe();
}

std::string case_name(const ::testing::TestParamInfo<Chi2Case> &info) { return info.param.name(); }

INSTANTIATE_TEST_SUITE_P(Diffuse, ChiSquare, ::testing::ValuesIn(diffuse_cases()), case_name);
INSTANTIATE_TEST_SUITE_P(Conductor, ChiSquare, ::testing::ValuesIn(conductor_cases()), case_name);
INSTANTIATE_TEST_SUITE_P(Dielectric, ChiSquare, ::testing::ValuesIn(dielectric_cases()), case_name);

// The harness itself: it must accept an exactly known sampler and reject wrong ones.
TEST(ChiSquareHarness, AcceptsCosineHemisphere) {
  const DirectionSampler sampler = [](Pcg32 &rng) -> std::optional<Vec3f> {
    const Vec2f u = rng.uniform2();
    return sample_cosine_hemisphere(u.x, u.y);
  };
  const DirectionPdf pdf = [](const Vec3f &w) { return cosine_hemisphere_pdf(w.z); };
  const ChiSquareResult r = chi_square_test(sampler, pdf, ChiSquareConfig{});
  EXPECT_TRUE(r.error.empty()) << r.describe();
  EXPECT_GE(r.p_value, kSignificance) << r.describe();
  EXPECT_NEAR(r.pdf_integral, 1, 1e-6);
}

bool rejected(const ChiSquareResult &r) { return !r.error.empty() || r.p_value < kSignificance; }

TEST(ChiSquareHarness, RejectsInflatedPdf) {
  const ChiSquareResult r = bsdf_chi_square(conductor_case(0.2f).bsdf, direction_deg(30), 7, 1.2);
  EXPECT_TRUE(rejected(r)) << r.describe();
}

TEST(ChiSquareHarness, RejectsSkewedSampler) {
  const ChiSquareResult r = bsdf_chi_square(dielectric_case(1.5f, 0.3f).bsdf, direction_deg(40), 7, 1, 1.05f);
  EXPECT_TRUE(rejected(r)) << r.describe();
}

// Sensitivity: samples from alpha = 0.2 against the pdf of alpha = 0.21.
TEST(ChiSquareHarness, RejectsSlightlyWrongRoughness) {
  const Bsdf sampled = conductor_case(0.2f).bsdf, claimed = conductor_case(0.21f).bsdf;
  const Vec3f wo = direction_deg(30);
  const DirectionSampler sampler = [&](Pcg32 &rng) -> std::optional<Vec3f> {
    const BsdfSample s = sampled.sample(wo, rng.uniform(), rng.uniform2(), TransportMode::Radiance);
    if (s.pdf == 0) return std::nullopt;
    return s.wi;
  };
  const DirectionPdf pdf = [&](const Vec3f &wi) { return claimed.pdf(wo, wi, TransportMode::Radiance); };
  const ChiSquareResult r = chi_square_test(sampler, pdf, ChiSquareConfig{});
  EXPECT_TRUE(rejected(r)) << r.describe();
}

}  // namespace chi_square_test_file
}  // namespace nimbus::test
