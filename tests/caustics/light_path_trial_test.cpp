// The light-path trial (light_path_trial.hpp): it alternates passes with and without light paths,
// measures each arm's per-iteration variance from the pixels' camera samples plus the light splatted
// into them (against the variances the test draws), keeps light paths exactly when variance times work
// is lower with them, and its state's round trip mid-trial changes nothing.
#include <gtest/gtest.h>

#include <random>

#include "light_path_trial.hpp"
#include "state_bytes.hpp"

namespace nimbus::caustics {
namespace light_path_trial_test {

constexpr size_t kPixels = 20000;
constexpr double kMean = 1.0;

struct Arm {
  double sigma;  // the per-iteration standard deviation of a pixel's light
  double work;   // work per camera path of a pass
};

// One pass: every pixel's light is kMean plus noise of its arm's sigma; with light paths, a third of it
// arrives as splats before the camera sample (noise split between the two).
void run_pass(LightPathTrial &t, std::mt19937_64 &rng, const Arm &off, const Arm &on) {
  const bool with = t.next_pass();
  const Arm &arm = with ? on : off;
  std::normal_distribution<double> noise(0.0, arm.sigma / std::sqrt(2.0));
  for (size_t i = 0; i < kPixels; ++i) {
    double camera = kMean + noise(rng);
    if (with) {
      const double splat = kMean / 3 + noise(rng);
      t.add_splat(i, float(splat));
      camera -= kMean / 3;
    } else {
      camera += noise(rng);
    }
    t.add_sample(i, float(camera));
  }
  t.pass_done(arm.work);
}

// What the trial should measure: sigma^2 weighted as relMSE weighs it.
double weighted(double sigma) { return sigma * sigma / (kMean * kMean + kRelativeOffset); }

void expect_decision(const Arm &off, const Arm &on, LightPathTrial::State want) {
  LightPathTrial t;
  t.reset(kPixels, true);
  std::mt19937_64 rng(7);
  for (uint32_t p = 0; p < 2 * kTrialIterations; ++p) {
    ASSERT_TRUE(t.measuring()) << "pass " << p;
    run_pass(t, rng, off, on);
  }
  EXPECT_EQ(t.state(), want);
  const LightPathTrial::Decision &d = t.decision();
  // Each arm's mean over 20000 pixels of a variance with kTrialIterations - 1 = 1 degree of freedom:
  // relative standard error sqrt(2 / 20000) = 1 %, plus under 1 % from the weights' noisy means
  // (sigma 0.1 of 1); 5 % is over 4 sigma.
  EXPECT_NEAR(d.v_off, weighted(off.sigma), 0.05 * weighted(off.sigma));
  EXPECT_NEAR(d.v_on, weighted(on.sigma), 0.05 * weighted(on.sigma));
  EXPECT_DOUBLE_EQ(d.c_off, off.work);
  EXPECT_DOUBLE_EQ(d.c_on, on.work);
  // Decided: later passes follow the decision and measure nothing.
  EXPECT_FALSE(t.measuring());
  EXPECT_EQ(t.next_pass(), want == LightPathTrial::State::On);
}

TEST(LightPathTrial, KeepsLightPathsWhereVarianceTimesWorkIsLower) {
  // Half the variance for 1.5x the work: 0.75 < 1.
  expect_decision({0.1, 10}, {0.1 / std::sqrt(2.0), 15}, LightPathTrial::State::On);
  // 10 % less variance for 1.5x the work: 1.35 > 1.
  expect_decision({0.1, 10}, {0.1 * std::sqrt(0.9), 15}, LightPathTrial::State::Off);
}

TEST(LightPathTrial, AlternatesUntilBothArmsAreMeasured) {
  LightPathTrial t;
  t.reset(kPixels, true);
  std::mt19937_64 rng(3);
  int with = 0;
  for (uint32_t p = 0; p + 1 < 2 * kTrialIterations; ++p) {
    with += t.next_pass() ? 1 : 0;
    t.pass_done(1.0);
  }
  EXPECT_EQ(with, int(kTrialIterations) - 1);
  EXPECT_TRUE(t.measuring());
}

TEST(LightPathTrial, WithoutLightPathsThereIsNoTrial) {
  LightPathTrial t;
  t.reset(kPixels, false);
  EXPECT_EQ(t.state(), LightPathTrial::State::Off);
  EXPECT_FALSE(t.next_pass());
  EXPECT_FALSE(t.measuring());
}

// A render saved mid-trial and resumed decides exactly as one that ran on.
TEST(LightPathTrial, StateRoundTripMidTrialDecidesTheSame) {
  const Arm off{0.1, 10}, on{0.08, 14};
  LightPathTrial a;
  a.reset(kPixels, true);
  std::mt19937_64 rng_a(11);
  for (int p = 0; p < 3; ++p) run_pass(a, rng_a, off, on);
  Bytes bytes;
  a.save(bytes);
  LightPathTrial b;
  b.reset(kPixels, true);
  ASSERT_TRUE(b.restore(bytes));
  std::mt19937_64 rng_b = rng_a;
  for (uint32_t p = 3; p < 2 * kTrialIterations; ++p)
    run_pass(a, rng_a, off, on), run_pass(b, rng_b, off, on);
  EXPECT_EQ(a.state(), b.state());
  EXPECT_EQ(a.decision().v_on, b.decision().v_on);
  EXPECT_EQ(a.decision().v_off, b.decision().v_off);
  // A state of another image size is refused.
  LightPathTrial c;
  c.reset(kPixels + 1, true);
  Bytes again;
  LightPathTrial d;
  d.reset(kPixels, true);
  std::mt19937_64 rng_d(5);
  run_pass(d, rng_d, off, on);
  d.save(again);
  EXPECT_FALSE(c.restore(again));
}

}  // namespace light_path_trial_test
}  // namespace nimbus::caustics
