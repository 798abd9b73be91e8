// Environment emission (environment_emission.hpp, solver spec 6.2): uniform and dim-gradient maps emit
// nothing; a bright lobe is sampled as its pdf says (chi-square) and the pdf integrates to one; a sun
// smaller than a cell keeps its weight, and every sample's pdf is the one the camera side evaluates.
#include <gtest/gtest.h>

#include <cmath>

#include "chi_square.hpp"
#include "emission_cone.hpp"
#include "environment_emission.hpp"

namespace nimbus::caustics {
namespace environment_emission_test {

using test::ChiSquareConfig;
using test::Pcg32;

// A light whose own sampler is uniform over the sphere, with luminance L(w).
template <class L>
auto uniform_sampler(L luminance) {
  return [luminance](float u0, float u1) {
    const Vec3f w = EnvironmentEmission::direction(u0, u1);
    return EnvironmentEmission::LightDirection{w, float(luminance(w)), 1 / (4 * kPi)};
  };
}

TEST(CausticsEnvironmentEmission, UniformAndDimGradientMapsEmitNothing) {
  EnvironmentEmission uniform_map;
  uniform_map.build(uniform_sampler([](const Vec3f &) { return 3.0f; }));
  EXPECT_FALSE(uniform_map.emits());
  EXPECT_EQ(uniform_map.pdf(Vec3f(0, 0, 1)), 0.0f);
  // An overcast sky brightest at the zenith: peak 1.9, mean 1, below twice the mean everywhere.
  EnvironmentEmission sky;
  sky.build(uniform_sampler([](const Vec3f &w) { return 1.0f + 0.9f * w.z; }));
  EXPECT_FALSE(sky.emits());
  EnvironmentEmission black;
  black.build(uniform_sampler([](const Vec3f &) { return 0.0f; }));
  EXPECT_FALSE(black.emits());
  EXPECT_EQ(black.sample(0.5f, 0.5f, 0.5f).pdf, 0.0f);
}

// A bright lobe around d0 over a dim background.
Vec3f lobe_axis() { return normalize(Vec3f(0.3f, -0.5f, 0.8f)); }
float lobe(const Vec3f &w) { return 1.0f + 40.0f * std::pow(std::max(0.0f, dot(w, lobe_axis())), 8.0f); }

TEST(CausticsEnvironmentEmission, BrightLobeIsSampledAsItsPdfSays) {
  EnvironmentEmission env;
  env.build(uniform_sampler(lobe));
  ASSERT_TRUE(env.emits());
  ChiSquareConfig cfg;
  cfg.seed = 11;
  const auto result = test::chi_square_test(
      [&](Pcg32 &rng) -> std::optional<Vec3f> {
        const float u0 = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
        const EnvironmentEmission::Sample s = env.sample(u0, u1, u2);
        if (!(s.pdf > 0)) return std::nullopt;
        return s.dir;
      },
      [&](const Vec3f &w) { return double(env.pdf(w)); }, cfg);
  EXPECT_TRUE(result.error.empty()) << result.error;
  EXPECT_GT(result.p_value, 0.01) << result.describe();
  EXPECT_NEAR(result.pdf_integral, 1.0, 2e-3) << result.describe();
  // Nothing is emitted where the weight is cut: opposite the lobe the map is at its dim background.
  EXPECT_EQ(env.pdf(-lobe_axis()), 0.0f);
}

TEST(CausticsEnvironmentEmission, SunSmallerThanACellKeepsItsWeight) {
  // Suns in a uniform sky of luminance 1: the real sun's 0.27 degrees at 10^5, and a texel of a 4k map
  // (0.04 degrees, far below the 16 point samples a cell would get, 0.35 degrees apart) at 10^7.
  struct Sun {
    float radius_deg, luminance;
  };
  for (const Sun &s : {Sun{0.27f, 1e5f}, Sun{0.04f, 1e7f}}) {
    const Vec3f sun = normalize(Vec3f(-0.2f, 0.6f, 0.5f));
    // The light samples half uniformly, half within the sun's cone (as an environment light's luminance
    // sampler would); a uniform sampler alone would rarely find the sun.
    const EmissionCone cone = EmissionCone::towards(Vec3f(0), sun, std::sin(s.radius_deg * kPi / 180));
    const auto luminance = [&](const Vec3f &w) { return cone.contains(w) ? s.luminance : 1.0f; };
    EnvironmentEmission env;
    env.build([&](float u0, float u1) {
      const Vec3f w = u0 < 0.5f ? EnvironmentEmission::direction(2 * u0, u1) : cone.sample(2 * u0 - 1, u1);
      const float pdf = 0.5f / (4 * kPi) + (cone.contains(w) ? 0.5f * cone.pdf() : 0.0f);
      return EnvironmentEmission::LightDirection{w, luminance(w), pdf};
    });
    ASSERT_TRUE(env.emits());
    // The weight keeps about the sun's share of the map's luminance and drops the sky. The sun's cell
    // mean is a ratio of sums over the ~32 sky samples that land in its cell besides the sun's, so it
    // carries their noise (1/sqrt(32), ~18 %): within 40 % of the sun's share.
    const double sun_flux = double(s.luminance) * 2 * kPi * (1 - std::cos(double(s.radius_deg) * kPi / 180));
    const double share = sun_flux / (sun_flux + 4 * kPi);
    EXPECT_NEAR(env.emitted_share(), share, 0.4 * share) << "sun of " << s.radius_deg << " degrees";
    Pcg32 rng(5);
    int near_sun = 0, consistent = 0;
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
      const float u0 = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
      const EnvironmentEmission::Sample e = env.sample(u0, u1, u2);
      ASSERT_GT(e.pdf, 0.0f);
      near_sun += dot(e.dir, sun) > std::cos(3.0f * kPi / 180);  // within ~2 cells
      consistent += std::abs(env.pdf(e.dir) - e.pdf) <= 1e-5f * e.pdf;
    }
    EXPECT_EQ(near_sun, n);
    // A direction on a cell's edge may round into its neighbour; never more than a few in 10^4.
    EXPECT_GE(consistent, n - 5);
  }
}

TEST(CausticsEnvironmentEmission, DensityIntegratesToOneOverTheSphere) {
  EnvironmentEmission env;
  env.build(uniform_sampler(lobe));
  // Cell centres of the equal-area grid: each cell spans 4 pi / cells of solid angle.
  const uint32_t cols = EnvironmentEmission::kColumns, rows = EnvironmentEmission::kRows;
  double integral = 0;
  for (uint32_t r = 0; r < rows; ++r)
    for (uint32_t c = 0; c < cols; ++c)
      integral += env.pdf(EnvironmentEmission::direction((c + 0.5f) / cols, (r + 0.5f) / rows));
  integral *= 4 * kPi / double(cols * rows);
  EXPECT_NEAR(integral, 1.0, 1e-4);
}

}  // namespace environment_emission_test
}  // namespace nimbus::caustics
