// The light-path trial (light_path_trial.hpp): from the same passes it measures the per-pass variance
// of each pixel's light with light paths (camera sample plus every splat) and without them (the
// sample's light without them plus the splats that would remain), against the variances the test
// draws; it keeps light paths exactly when variance times work is lower with them, decides early when
// the two are far apart, stops measuring once decided, and its state's round trip mid-trial changes
// nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "light_path_trial.hpp"
#include "state_bytes.hpp"

namespace nimbus::caustics {
namespace light_path_trial_test {

constexpr size_t kPixels = 20000;
constexpr double kMean = 1.0;

struct Arms {
  double sigma_without, sigma_with;  // per-pass standard deviation of a pixel's light
  double work, light_path_work;      // work per camera path of a pass, and the light paths' share
};

// One pass: each pixel's light without light paths is kMean plus noise; with them, a third arrives as
// light-path splats before the camera sample, and the rest carries its own noise.
void run_pass(LightPathTrial &t, std::mt19937_64 &rng, const Arms &a) {
  std::normal_distribution<double> without(0.0, a.sigma_without), with(0.0, a.sigma_with / std::sqrt(2.0));
  for (size_t i = 0; i < kPixels; ++i) {
    const double light_paths = kMean / 3 + with(rng);
    t.add_splat(i, float(light_paths), 0.0f);
    t.add_sample(i, float(2 * kMean / 3 + with(rng)), float(kMean + without(rng)));
  }
  t.pass_done(a.work, a.light_path_work);
}

// What the trial should measure: sigma^2 weighted as relMSE weighs it.
double weighted(double sigma) { return sigma * sigma / (kMean * kMean + kRelativeOffset); }

// Runs passes until the trial decides; it should decide `want` after `passes` passes.
void expect_decision(const Arms &a, LightPathTrial::State want, uint32_t passes) {
  LightPathTrial t;
  t.reset(kPixels, true);
  std::mt19937_64 rng(7);
  uint32_t run = 0;
  while (t.measuring() && run < kTrialIterations) {
    EXPECT_TRUE(t.light_paths());
    run_pass(t, rng, a);
    ++run;
  }
  EXPECT_EQ(run, passes);
  EXPECT_EQ(t.state(), want);
  const LightPathTrial::Decision &d = t.decision();
  // Each arm's mean over 20000 pixels of a variance with passes - 1 degrees of freedom: relative
  // standard error sqrt(2 / (passes - 1) / 20000) (1.0 % after 2 passes, 0.58 % after 4), plus under
  // 0.3 % from the weights' noisy means (sigma 0.1 of 1): 4 of the former plus 0.5 %.
  const double tol = 4 * std::sqrt(2.0 / (passes - 1) / kPixels) + 0.005;
  EXPECT_NEAR(d.v_off, weighted(a.sigma_without), tol * weighted(a.sigma_without));
  EXPECT_NEAR(d.v_on, weighted(a.sigma_with), tol * weighted(a.sigma_with));
  EXPECT_DOUBLE_EQ(d.c_off, a.work - a.light_path_work);
  EXPECT_DOUBLE_EQ(d.c_on, a.work);
  // Decided: nothing more is measured, and light paths follow the decision.
  EXPECT_FALSE(t.measuring());
  EXPECT_EQ(t.light_paths(), want == LightPathTrial::State::On);
}

TEST(LightPathTrial, KeepsLightPathsWhereVarianceTimesWorkIsLower) {
  // Far apart, decided after kEarlyIterations passes. Half the variance for 1.5x the work: 0.75 < 1.
  expect_decision({0.1, 0.1 / std::sqrt(2.0), 15, 5}, LightPathTrial::State::On, kEarlyIterations);
  // 10 % less variance for 1.5x the work: 1.35 > 1.
  expect_decision({0.1, 0.1 * std::sqrt(0.9), 15, 5}, LightPathTrial::State::Off, kEarlyIterations);
  // Within kEarlyMargin, decided after kTrialIterations. 40 % less variance for 1.5x the work: 0.9 < 1.
  expect_decision({0.1, 0.1 * std::sqrt(0.6), 15, 5}, LightPathTrial::State::On, kTrialIterations);
  // 25 % less variance for 1.5x the work: 1.125 > 1.
  expect_decision({0.1, 0.1 * std::sqrt(0.75), 15, 5}, LightPathTrial::State::Off, kTrialIterations);
}

TEST(LightPathTrial, WithoutLightPathsThereIsNoTrial) {
  LightPathTrial t;
  t.reset(kPixels, false);
  EXPECT_EQ(t.state(), LightPathTrial::State::Off);
  EXPECT_FALSE(t.light_paths());
  EXPECT_FALSE(t.measuring());
}

// A render saved mid-trial and resumed decides exactly as one that ran on; a state of another image
// size is refused.
TEST(LightPathTrial, StateRoundTripMidTrialDecidesTheSame) {
  const Arms arms{0.1, 0.08, 14, 4};  // 0.64 x 1.4 = 0.9: within kEarlyMargin, decided after 4 passes
  LightPathTrial a;
  a.reset(kPixels, true);
  std::mt19937_64 rng_a(11);
  for (int p = 0; p < 3; ++p) run_pass(a, rng_a, arms);
  Bytes bytes;
  a.save(bytes);
  LightPathTrial b;
  b.reset(kPixels, true);
  ASSERT_TRUE(b.restore(bytes));
  std::mt19937_64 rng_b = rng_a;
  for (uint32_t p = 3; p < kTrialIterations; ++p) run_pass(a, rng_a, arms), run_pass(b, rng_b, arms);
  EXPECT_FALSE(a.measuring());
  EXPECT_EQ(a.state(), b.state());
  EXPECT_EQ(a.decision().v_on, b.decision().v_on);
  EXPECT_EQ(a.decision().v_off, b.decision().v_off);
  Bytes mid;
  LightPathTrial d;
  d.reset(kPixels, true);
  run_pass(d, rng_b, arms);
  d.save(mid);
  LightPathTrial c;
  c.reset(kPixels + 1, true);
  EXPECT_FALSE(c.restore(mid));
}

}  // namespace light_path_trial_test
}  // namespace nimbus::caustics
