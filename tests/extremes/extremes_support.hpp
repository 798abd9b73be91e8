// Shared by the numerical-extremes tests: a render that also returns the film's non-finite sample count,
// YAML number formatting that survives 1e-4..1e6 scales, and the statistics the tests compare with.
//
// Every test asserts that the film dropped no non-finite sample (nimbus:nonfinite_samples == 0). That the
// film itself counts a NaN/Inf sample and keeps the pixel finite is tested directly in
// tests/film/accumulate_test.cpp (FilmAccumulate.NonFiniteSamplesAreCountedAndNeverReachTheFilm) and
// tests/film/splat_test.cpp (FilmSplat.BadSplatsAreDroppedAndNonFiniteOnesCounted); not repeated here.
//
// Statistics: every pixel is an independent estimate (its random numbers derive from its own index), so
// the per-pixel differences between two renders of the same expected image are independent with mean
// zero, and their spread gives the standard error of their mean without knowing the image itself.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>
#include <vector>

#include "support/render_support.hpp"

namespace nimbus::extremes {

using testing::RenderRequest;
using testing::SceneRenderer;

// A path-traced render request; `sampler` empty = the host's choice of light sampler.
inline RenderRequest pt(uint64_t iterations, uint64_t seed, const std::string &sampler = {}) {
  RenderRequest r;
  r.integrator = "nimbus.pt";
  r.iterations = iterations;
  r.seed = seed;
  r.light_sampler = sampler;
  return r;
}

struct Rendered {
  uint32_t width = 0, height = 0;
  std::vector<float> rgb;  // beauty, interleaved
  uint64_t nonfinite = 0;  // samples the film dropped as NaN/Inf (EXR nimbus:nonfinite_samples)
  uint64_t iterations = 0;
  bool ok = false;

  float at(uint32_t x, uint32_t y, int c) const { return rgb[3 * (size_t(y) * width + x) + c]; }
};

// Renders and reads back the beauty and the film's counters; a missing layer or header fails the test.
inline Rendered render(SceneRenderer &r, const std::string &yaml, const RenderRequest &req) {
  Rendered out;
  const ImageLayers img = r.render(yaml, req);
  const auto beauty = img.layers.find("beauty");
  const auto nonfinite = img.numbers.find("nimbus:nonfinite_samples");
  const auto iterations = img.numbers.find("nimbus:iterations");
  if (beauty == img.layers.end() || nonfinite == img.numbers.end() || iterations == img.numbers.end()) {
    ADD_FAILURE() << "render produced no beauty layer or no nimbus:nonfinite_samples / nimbus:iterations";
    return out;
  }
  out.width = img.width, out.height = img.height;
  out.rgb = beauty->second.data;
  out.nonfinite = uint64_t(nonfinite->second);
  out.iterations = uint64_t(iterations->second);
  out.ok = out.iterations == req.iterations && out.rgb.size() == size_t(3) * out.width * out.height;
  EXPECT_TRUE(out.ok) << "expected " << req.iterations << " iterations, got " << out.iterations;
  for (float v : out.rgb)
    if (!std::isfinite(v)) {
      ADD_FAILURE() << "a non-finite value reached the EXR";
      break;
    }
  return out;
}

// The scene `yaml` parses (its `what`, for the message): a parser regression fails the test here, naming
// the parser's error, rather than turning into a skip or a failure on an empty scene.
#define NIMBUS_ASSERT_PARSES(yaml, what)                                                             \
  do {                                                                                               \
    auto parsed_ = parse_scene_string(yaml, "probe.yaml");                                           \
    ASSERT_TRUE(parsed_.ok()) << what << " not accepted by the parser: " << parsed_.error().message; \
  } while (0)

// Decimal text for YAML that parses back to the nearest float (9 significant digits round-trip floats).
inline std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}
inline std::string vec(double x, double y, double z) {
  return "[" + num(x) + ", " + num(y) + ", " + num(z) + "]";
}

// NIMBUS_EXTREMES_VERBOSE=1 prints the measured statistics, for recalibrating documented bounds.
inline bool verbose() {
  static const bool on = std::getenv("NIMBUS_EXTREMES_VERBOSE") != nullptr;
  return on;
}

// Which pixels a statistic covers; empty = all.
using PixelMask = std::function<bool(uint32_t x, uint32_t y)>;

struct Estimate {
  double mean = 0, std_error = 0;
  size_t n = 0;
};

// Mean over the masked pixels of f(x, y), with its standard error from the pixels' spread (valid when
// the pixels share one expected value, or as a conservative bound when they do not).
inline Estimate estimate(uint32_t width, uint32_t height, const std::function<double(uint32_t, uint32_t)> &f,
                         const PixelMask &mask = {}) {
  double sum = 0, sum2 = 0;
  size_t n = 0;
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      if (mask && !mask(x, y)) continue;
      const double v = f(x, y);
      sum += v, sum2 += v * v, ++n;
    }
  Estimate e;
  e.n = n;
  if (n == 0) return e;
  e.mean = sum / double(n);
  const double var = n > 1 ? std::max(0.0, (sum2 - sum * e.mean) / double(n - 1)) : 0.0;
  e.std_error = std::sqrt(var / double(n));
  return e;
}

// Channel c (0..2) of one image over a region.
inline Estimate channel_mean(const Rendered &a, int c, const PixelMask &mask = {}) {
  return estimate(
      a.width, a.height, [&](uint32_t x, uint32_t y) { return double(a.at(x, y, c)); }, mask);
}

// Per-pixel difference test - ref of channel c: its mean is the bias between the two renders.
inline Estimate paired_difference(const Rendered &test, const Rendered &ref, int c,
                                  const PixelMask &mask = {}) {
  return estimate(
      ref.width, ref.height,
      [&](uint32_t x, uint32_t y) { return double(test.at(x, y, c)) - ref.at(x, y, c); }, mask);
}

// test and ref estimate the same image: per channel, their mean difference is within `sigmas` standard
// errors of zero or within `rel_floor` of ref's mean (the floor covers two renders so correlated - same
// seed - that their difference is nearly noise-free while legitimate float rounding still differs).
inline void expect_same_image_mean(const Rendered &test, const Rendered &ref, const std::string &what,
                                   double sigmas = 5, double rel_floor = 2e-3, const PixelMask &mask = {}) {
  ASSERT_EQ(test.width, ref.width);
  ASSERT_EQ(test.height, ref.height);
  for (int c = 0; c < 3; ++c) {
    const Estimate d = paired_difference(test, ref, c, mask);
    const Estimate m = channel_mean(ref, c, mask);
    const double tol = std::max(sigmas * d.std_error, rel_floor * std::abs(m.mean));
    if (verbose())
      std::printf("  %s ch%d: ref %.6g diff %.3g (%.2f std errors, %.3g relative)\n", what.c_str(), c, m.mean,
                  d.mean, d.std_error > 0 ? d.mean / d.std_error : 0.0, m.mean != 0 ? d.mean / m.mean : 0.0);
    EXPECT_LE(std::abs(d.mean), tol) << what << ", channel " << c << ": mean " << m.mean + d.mean
                                     << " vs reference " << m.mean << " (difference " << d.mean
                                     << ", std error " << d.std_error << ", " << d.n << " pixels)";
  }
}

}  // namespace nimbus::extremes
