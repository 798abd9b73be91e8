// core/spectral_uplift.hpp and core/rgb_uplift_table.hpp: the fitted spectrum's RGB, integrated at 0.1 nm
// independently of the fit's own 2.5 nm rule, against the colour it was fitted to; the shape the model
// promises (bounded, at most one extremum, flat for greys); emission scaling; the table against the colour.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <random>
#include <thread>
#include <vector>

#include <nimbus/cpp/spectral.hpp>
#include "core/rgb_uplift_table.hpp"
#include "core/spectral_uplift.hpp"

namespace nimbus {
namespace spectral_uplift_test {

// Simpson's rule at 0.1 nm with the weights tabulated once: a reference 25 times finer than the fit's.
class FineIntegrator {
 public:
  FineIntegrator() {
    for (int k = 0; k <= kSteps; ++k) {
      lambda_.push_back(kLambdaMin + (kLambdaMax - kLambdaMin) * float(k) / kSteps);
      const double simpson = (k == 0 || k == kSteps) ? 1 : (k % 2 == 1 ? 4 : 2);
      weight_.push_back(spectral_rgb_weight(lambda_.back()) *
                        float(simpson * (kLambdaMax - kLambdaMin) / kSteps / 3));
    }
  }
  Vec3f rgb(const SigmoidSpectrum &s) const {
    double sum[3] = {0, 0, 0};
    for (size_t k = 0; k < lambda_.size(); ++k) {
      const double v = s(lambda_[k]);
      for (int c = 0; c < 3; ++c) sum[c] += v * weight_[k][c];
    }
    return {float(sum[0]), float(sum[1]), float(sum[2])};
  }

 private:
  static constexpr int kSteps = 4700;
  std::vector<float> lambda_;
  std::vector<Vec3f> weight_;
};

const FineIntegrator &fine() {
  static const FineIntegrator f;
  return f;
}

float rgb_error(const SigmoidSpectrum &s, const Vec3f &rgb) {
  return max_component(abs(fine().rgb(s) - rgb));
}

// The model reaches every colour but the dark saturated ones and, since 1 - s(x) = s(-x), their complements
// near white: those whose brightest channel is below ~0.025 or whose darkest is above ~0.975.
bool reachable(const Vec3f &rgb) {
  const float lo = std::min({rgb.x, rgb.y, rgb.z}), hi = max_component(rgb);
  return lo == hi || (hi >= 0.03f && lo <= 0.97f);
}

std::vector<Vec3f> test_colours() {
  std::vector<Vec3f> colours;
  for (int r = 0; r <= 10; ++r)
    for (int g = 0; g <= 10; ++g)
      for (int b = 0; b <= 10; ++b) colours.push_back(Vec3f(float(r), float(g), float(b)) * 0.1f);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0, 1);
  for (int i = 0; i < 1000; ++i) colours.push_back({u(rng), u(rng), u(rng)});
  // Near black and white, where the model runs out of reach.
  for (int i = 0; i < 500; ++i) {
    const Vec3f dark = Vec3f(u(rng), u(rng), u(rng)) * (0.05f * u(rng));
    colours.push_back(i % 2 ? dark : Vec3f(1) - dark);
  }
  return colours;
}

TEST(ReflectanceFit, RoundTripsEveryReachableColour) {
  float worst_reachable = 0, worst_other = 0;
  Vec3f at_reachable, at_other;
  for (const Vec3f &rgb : test_colours()) {
    const float err = rgb_error(fit_reflectance(rgb), rgb);
    float &worst = reachable(rgb) ? worst_reachable : worst_other;
    if (err > worst) worst = err, (reachable(rgb) ? at_reachable : at_other) = rgb;
  }
  std::printf(
      "fit round trip: max RGB error %.3g reachable (at %g %g %g), %.3g near black/white (at %g %g %g)\n",
      worst_reachable, at_reachable.x, at_reachable.y, at_reachable.z, worst_other, at_other.x, at_other.y,
      at_other.z);
  // Reachable: the fit stops within 1e-6 by its own rule, which differs from the 0.1 nm one by up to 5e-5
  // for the sharpest (most saturated) spectra.
  EXPECT_LT(worst_reachable, 1e-4f);
  // Out of reach, the closest spectrum misses by up to 1.2e-3 (near (0.005, 0, 0) and its complement).
  EXPECT_LT(worst_other, 1.5e-3f);
}

TEST(ReflectanceFit, PrimariesAndSecondariesAreReached) {
  for (Vec3f rgb :
       {Vec3f(1, 0, 0), Vec3f(0, 1, 0), Vec3f(0, 0, 1), Vec3f(1, 1, 0), Vec3f(0, 1, 1), Vec3f(1, 0, 1)})
    EXPECT_LT(rgb_error(fit_reflectance(rgb), rgb), 1e-4f) << rgb.x << " " << rgb.y << " " << rgb.z;
}

TEST(ReflectanceFit, GreysAreFlatAndExactAtTheEnds) {
  for (int i = 0; i <= 20; ++i) {
    const float g = float(i) / 20;
    const SigmoidSpectrum s = fit_reflectance(Vec3f(g));
    EXPECT_EQ(s.c0, 0.0f);
    EXPECT_EQ(s.c1, 0.0f);
    for (float l = kLambdaMin; l <= kLambdaMax; l += 47) EXPECT_NEAR(s(l), g, 1e-6f) << "grey " << g;
  }
  // Black and white evaluate to exactly 0 and 1 in float (the exact sigmoid is 2.5e-9 from them).
  EXPECT_EQ(fit_reflectance(Vec3f(0))(550), 0.0f);
  EXPECT_EQ(fit_reflectance(Vec3f(1))(550), 1.0f);
  // Out-of-range channels clamp.
  EXPECT_EQ(fit_reflectance(Vec3f(-1, -2, -3))(550), 0.0f);
  EXPECT_EQ(fit_reflectance(Vec3f(2, 3, 4))(550), 1.0f);
}

// Direction changes of s over the visible range at 1 nm, ignoring float noise of a few ulps on plateaus.
int extrema(const SigmoidSpectrum &s) {
  int changes = 0, direction = 0;
  float previous = s(kLambdaMin);
  for (float l = kLambdaMin + 1; l <= kLambdaMax; l += 1) {
    const float v = s(l), d = v - previous;
    previous = v;
    if (std::abs(d) < 1e-6f) continue;
    const int dir = d > 0 ? 1 : -1;
    if (direction != 0 && dir != direction) ++changes;
    direction = dir;
  }
  return changes;
}

TEST(ReflectanceFit, SpectraAreBoundedAndSmooth) {
  for (const Vec3f &rgb : test_colours()) {
    const SigmoidSpectrum s = fit_reflectance(rgb);
    for (float l = kLambdaMin; l <= kLambdaMax; l += 5) {
      ASSERT_GE(s(l), 0.0f);
      ASSERT_LE(s(l), 1.0f);
    }
    ASSERT_LE(extrema(s), 1) << rgb.x << " " << rgb.y << " " << rgb.z;
  }
}

TEST(EmissionFit, ScalesToTwiceTheBrightestChannel) {
  for (Vec3f rgb : {Vec3f(5, 2, 0.5f), Vec3f(0.1f, 0.3f, 0.2f), Vec3f(40, 40, 40), Vec3f(0, 0, 3)}) {
    const UpliftedEmission e = fit_emission(rgb);
    EXPECT_EQ(e.scale, 2 * max_component(rgb));
    const Vec3f back = fine().rgb(e.shape) * e.scale;
    EXPECT_LT(max_component(abs(back - rgb)), 1e-4f * e.scale) << rgb.x << " " << rgb.y << " " << rgb.z;
    EXPECT_NEAR(e(550), e.scale * e.shape(550), 1e-6f * e.scale);
  }
  EXPECT_EQ(fit_emission(Vec3f(0)).scale, 0.0f);
  EXPECT_EQ(fit_emission(Vec3f(0))(550), 0.0f);
}

TEST(RgbUpliftTable, LookupsMatchTheColour) {
  const auto start = std::chrono::steady_clock::now();
  const RgbUpliftTable table;
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("uplift table: resolution %d, built in %.3f s, largest cell error %.3g\n", table.resolution(),
              seconds, table.max_cell_error());
  float worst_inner = 0, worst_outer = 0, worst_vs_fit = 0;
  for (const Vec3f &rgb : test_colours()) {
    const float err = rgb_error(table.lookup(rgb), rgb);
    const float lo = std::min({rgb.x, rgb.y, rgb.z}), hi = max_component(rgb);
    float &worst = (hi >= 0.05f && lo <= 0.95f) ? worst_inner : worst_outer;
    worst = std::max(worst, err);
    worst_vs_fit = std::max(worst_vs_fit, err - rgb_error(fit_reflectance(rgb), rgb));
  }
  std::printf(
      "uplift table lookups: max RGB error %.3g (>= 0.05 from black and white), %.3g nearer; at most "
      "%.3g beyond the direct fit's\n",
      worst_inner, worst_outer, worst_vs_fit);
  // Trilinear interpolation of coefficients is second order in the node spacing: 8.8e-4 measured at
  // resolution 48 over 20,000 random colours. Nearer black and white, between reachable nodes and
  // unreachable ones whose coefficients run to the fit's bound, it reaches 4.5e-3.
  EXPECT_LT(worst_inner, 1.5e-3f);
  EXPECT_LT(worst_outer, 6e-3f);
  for (int i = 0; i <= 10; ++i)
    EXPECT_EQ(table.lookup(Vec3f(i * 0.1f)).c2, fit_reflectance(Vec3f(i * 0.1f)).c2);
}

TEST(RgbUpliftTable, SharedTableIsBuiltOnceForConcurrentUsers) {
  const RgbUpliftTable *seen[2] = {};
  Vec3f values[2];
  std::thread a([&] {
    seen[0] = &srgb_uplift_table(), values[0] = fine().rgb(seen[0]->lookup({0.2f, 0.5f, 0.7f}));
  });
  std::thread b([&] {
    seen[1] = &srgb_uplift_table(), values[1] = fine().rgb(seen[1]->lookup({0.2f, 0.5f, 0.7f}));
  });
  a.join(), b.join();
  EXPECT_EQ(seen[0], seen[1]);
  EXPECT_EQ(values[0], values[1]);
  const UpliftedEmission e = srgb_uplift_table().lookup_emission({8, 4, 1});
  EXPECT_EQ(e.scale, 16.0f);
  EXPECT_LT(max_component(abs(fine().rgb(e.shape) * e.scale - Vec3f(8, 4, 1))), 16 * 1.5e-3f);
}

}  // namespace spectral_uplift_test
}  // namespace nimbus
