// The per-pixel statistics behind the photon budget (useful_pixels.hpp): the photon noise of a map's
// merges, measured from the map's two independent halves before a pixel has seen two maps (unbiased,
// against the variance the test draws), not from one sample per pixel, and not from a guided map's
// dependent halves; the state's round trip.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>
#include <thread>
#include <vector>

#include "state_bytes.hpp"
#include "useful_pixels.hpp"

namespace nimbus::caustics {
namespace useful_pixels_test {

constexpr size_t kPixels = 20000;
constexpr int kSamplesPerMap = 4;
constexpr double kMerge = 2.0, kPhotonSigma = 0.3, kCameraSigma = 0.5, kRest = 1.0;

// One map's camera samples of every pixel. Each pixel's map carries a photon error e_even + e_odd shared
// by its samples (the two halves' independent errors, each of variance sigma^2 / 2, so the map mean's
// photon variance is sigma^2); each sample adds its own camera-side noise to the merges, which both
// halves see alike. Returns each pixel's expected weight (UsefulPixels' 1 / (mean^2 + offset)) summed
// over the samples, for the expected summary.
std::vector<double> render_map(UsefulPixels &u, std::mt19937_64 &rng, bool with_split) {
  std::normal_distribution<double> half(0.0, kPhotonSigma / std::sqrt(2.0)), camera(0.0, kCameraSigma);
  std::vector<double> means(kPixels);
  for (size_t i = 0; i < kPixels; ++i) {
    const double e_even = half(rng), e_odd = half(rng);
    double total = 0;
    for (int k = 0; k < kSamplesPerMap; ++k) {
      const double m = kMerge + camera(rng) + e_even + e_odd;
      total += m + kRest;
      u.add(i, Rgb(float(m + kRest)), Rgb(float(m)), {0.0f, 0.0f}, with_split ? float(e_even - e_odd) : 0.0f);
    }
    means[i] = total / kSamplesPerMap;
  }
  return means;
}

// sigma^2 k / (mean^2 + offset) over the pixels: what v_merge estimates, with the window's means.
double expected_v_merge(const std::vector<double> &means, double iterations_per_map) {
  double sum = 0;
  for (double m : means) sum += kPhotonSigma * kPhotonSigma * iterations_per_map / (m * m + kRelativeOffset);
  return sum / double(means.size());
}

// Var(mean of D^2) for D ~ N(0, sigma^2): 2 sigma^4 per pixel, so the relative standard error of the
// summary is sqrt(2 / pixels) = 1 % here; the tolerance is 4 standard errors.
constexpr double kTolerance = 4 * 0.01;

TEST(UsefulPixels, AMapsHalvesMeasureItsPhotonNoiseFromTheFirstMap) {
  UsefulPixels u;
  u.reset(kPixels);
  u.map_changed(true);  // the probe: an unguided pass
  std::mt19937_64 rng(7);
  const std::vector<double> means = render_map(u, rng, true);
  const UsefulPixels::Summary s = u.summarize(kPixels, 2.0);
  const double expected = expected_v_merge(means, 2.0);
  EXPECT_NEAR(s.v_merge / expected, 1.0, kTolerance) << s.v_merge << " against " << expected;
  EXPECT_DOUBLE_EQ(s.useful, 1.0);
}

TEST(UsefulPixels, OneSamplePerPixelMeasuresNothing) {
  // A single sample has no spread for the camera side's variance: the budget would see merges alone.
  UsefulPixels u;
  u.reset(4);
  u.map_changed(true);
  for (size_t i = 0; i < 4; ++i) u.add(i, Rgb(2.0f), Rgb(1.0f), {0.0f, 0.0f}, 0.5f);
  EXPECT_EQ(u.summarize(4, 2.0).v_merge, 0.0);
  for (size_t i = 0; i < 4; ++i) u.add(i, Rgb(2.0f), Rgb(1.0f), {0.0f, 0.0f}, 0.5f);
  // Two samples (the first decayed once), a half difference of 0.5 each: 0.25 x 2 / (2^2 + 0.01).
  EXPECT_NEAR(u.summarize(4, 2.0).v_merge, 0.25 * 2 / 4.01, 1e-6);
}

TEST(UsefulPixels, AGuidedMapsHalvesAreNotUsed) {
  // Paths of a guided pass come from Markov chains: its halves are not independent, so nothing is
  // measured until two maps have been compared.
  UsefulPixels u;
  u.reset(kPixels);
  u.map_changed(false);
  std::mt19937_64 rng(8);
  render_map(u, rng, true);
  EXPECT_EQ(u.summarize(kPixels, 2.0).v_merge, 0.0);
}

TEST(UsefulPixels, TheStateRoundTripsWithTheMapsKind) {
  UsefulPixels a;
  a.reset(4);
  a.map_changed(true);
  for (size_t i = 0; i < 4; ++i) a.add(i, Rgb(2.0f), Rgb(1.0f), {0.0f, 0.0f}, 0.5f);
  Bytes bytes;
  a.save(bytes);
  UsefulPixels b;
  b.reset(4);
  ASSERT_TRUE(b.restore(bytes));
  for (size_t i = 0; i < 4; ++i) a.add(i, Rgb(2.0f), Rgb(1.0f), {0.0f, 0.0f}, 0.5f);
  for (size_t i = 0; i < 4; ++i) b.add(i, Rgb(2.0f), Rgb(1.0f), {0.0f, 0.0f}, 0.5f);
  EXPECT_EQ(a.summarize(4, 2.0).v_merge, b.summarize(4, 2.0).v_merge);
  EXPECT_GT(b.summarize(4, 2.0).v_merge, 0.0);
  UsefulPixels wrong;
  wrong.reset(5);
  Bytes again;
  a.save(again);
  EXPECT_FALSE(wrong.restore(again));
}

// Light splatted into a pixel before its sample (photon_splats.hpp) is photon light of that sample: a
// pixel whose caustic the splats carry alone is useful, and its split counts in the map's halves.
TEST(UsefulPixels, SplattedLightIsThePhotonsLight) {
  UsefulPixels u;
  u.reset(2);
  for (int k = 0; k < 4; ++k) {
    u.add_splat(0, 3.0f, k % 2 ? 1.0f : -1.0f);  // pixel 0: the splats carry its light
    u.add(0, Rgb(1.0f), Rgb(0.0f), {0.0f, 0.0f});
    u.add(1, Rgb(1.0f), Rgb(0.0f), {0.0f, 0.0f});  // pixel 1: no photon light at all
  }
  const UsefulPixels::Summary with = u.summarize(2, 1.0);
  EXPECT_DOUBLE_EQ(with.useful, 0.5);
  // The camera part (beauty minus photon light) is 1 in every sample: no camera variance; the pixel's
  // value, 4, weighs it.
  EXPECT_NEAR(with.v_camera, 0.0, 1e-12);
}

// The summary is summed in chunks of pixels that may run concurrently: the same bits from any runner,
// whatever order its chunks finish in (here: every chunk on its own thread, reversed start order).
TEST(UsefulPixels, TheSummaryDoesNotDependOnTheRunner) {
  const sdk::ParallelFor threads = [](size_t count, const std::function<void(size_t)> &fn) {
    std::vector<std::thread> pool;
    for (size_t c = count; c-- > 0;) pool.emplace_back([&fn, c] { fn(c); });
    for (std::thread &t : pool) t.join();
  };
  constexpr size_t kMany = 70000;  // several chunks, the last one partial
  UsefulPixels serial, parallel;
  serial.reset(kMany), parallel.reset(kMany);
  serial.map_changed(true), parallel.map_changed(true, threads);
  std::mt19937_64 rng(9);
  std::normal_distribution<float> noise(0.0f, 0.4f);
  for (int k = 0; k < 2 * kSamplesPerMap; ++k) {
    if (k == kSamplesPerMap) serial.map_changed(true), parallel.map_changed(true, threads);
    for (size_t i = 0; i < kMany; ++i) {
      const float m = std::abs(1.0f + noise(rng)), rest = std::abs(noise(rng)), split = noise(rng);
      const std::array<float, kLookupClasses> moment{m * m, rest};
      serial.add(i, Rgb(m + rest), Rgb(m), moment, split),
          parallel.add(i, Rgb(m + rest), Rgb(m), moment, split);
    }
    const UsefulPixels::Summary a = serial.summarize(kMany, 2.0), b = parallel.summarize(kMany, 2.0, threads);
    EXPECT_EQ(a.useful, b.useful);
    EXPECT_EQ(a.v_merge, b.v_merge);
    EXPECT_EQ(a.v_camera, b.v_camera);
    EXPECT_EQ(a.second_moment, b.second_moment);
    EXPECT_GT(a.v_camera, 0.0);
  }
}

}  // namespace useful_pixels_test
}  // namespace nimbus::caustics
