// A fixed seed gives the same image at any thread count, path and light tracer alike (random numbers
// derive from seed, pixel or path, iteration and dimension, never from thread identity or timing); a
// different seed gives another image.
// Pixels are compared as read back, not as file bytes, because the header records the render time.
#include <gtest/gtest.h>

#include <bit>
#include <cstring>

#include "e2e_support.hpp"

namespace nimbus::e2e {
namespace determinism_test {

struct Rendered {
  std::vector<float> rgb[3];
};

// Renders box.yaml with `--threads threads --seed seed` (and `integrator` if given); nullopt (with a
// failure recorded) if it fails.
std::optional<Rendered> render_box(const TestDir &dir, int threads, int seed,
                                   const std::string &integrator = "") {
  const std::string exr =
      dir.file(integrator + "t" + std::to_string(threads) + "-s" + std::to_string(seed) + ".exr");
  std::vector<std::string> args = {"render",
                                   scene("box.yaml"),
                                   "-o",
                                   exr,
                                   "-q",
                                   "--iterations",
                                   "8",
                                   "--threads",
                                   std::to_string(threads),
                                   "--seed",
                                   std::to_string(seed)};
  if (!integrator.empty()) args.insert(args.end(), {"--integrator", integrator});
  const ProcessResult r = run_nimbus(args, dir);
  if (!exited_with(r, 0)) {
    ADD_FAILURE() << r.describe();
    return std::nullopt;
  }
  const auto img = read_exr(exr);
  if (!img) return std::nullopt;
  // Otherwise the comparison would prove nothing: both runs must really have used what was asked.
  EXPECT_EQ(meta_number(*img, "nimbus:threads"), std::optional<double>(threads)) << exr;
  EXPECT_EQ(recorded_seed(*img), std::optional<uint64_t>(seed)) << exr;
  Rendered out;
  const char *names[3] = {"R", "G", "B"};
  for (int c = 0; c < 3; ++c) out.rgb[c] = plane(*img, names[c]);
  return out;
}

// Pixels whose bit patterns differ in any channel.
size_t differing_pixels(const Rendered &a, const Rendered &b) {
  size_t n = 0;
  for (size_t i = 0; i < a.rgb[0].size(); ++i) {
    bool differ = false;
    for (int c = 0; c < 3; ++c)
      differ |= std::bit_cast<uint32_t>(a.rgb[c][i]) != std::bit_cast<uint32_t>(b.rgb[c][i]);
    n += differ;
  }
  return n;
}

TEST(Determinism, SameSeedIsBitIdenticalAcrossThreadCounts) {
  TestDir dir;
  const auto one = render_box(dir, 1, 5);
  const auto two = render_box(dir, 2, 5);
  ASSERT_TRUE(one && two);
  for (int c = 0; c < 3; ++c) {
    ASSERT_EQ(one->rgb[c].size(), 64u * 48u);
    ASSERT_EQ(two->rgb[c].size(), one->rgb[c].size());
  }
  EXPECT_EQ(differing_pixels(*one, *two), 0u);
}

// The light tracer splats into pixels other threads' paths also reach: still the same image at any thread
// count, and another with another seed.
TEST(Determinism, LightTracerIsBitIdenticalAcrossThreadCounts) {
  TestDir dir;
  const auto one = render_box(dir, 1, 5, "lt"), two = render_box(dir, 2, 5, "lt"),
             other = render_box(dir, 2, 6, "lt");
  ASSERT_TRUE(one && two && other);
  ASSERT_EQ(one->rgb[0].size(), 64u * 48u);
  EXPECT_EQ(differing_pixels(*one, *two), 0u);
  EXPECT_GT(differing_pixels(*two, *other), one->rgb[0].size() / 2);
}

TEST(Determinism, DifferentSeedGivesDifferentImage) {
  TestDir dir;
  const auto a = render_box(dir, 2, 5);
  const auto b = render_box(dir, 2, 6);
  ASSERT_TRUE(a && b);
  ASSERT_EQ(a->rgb[0].size(), b->rgb[0].size());
  // Path tracing noise differs almost everywhere; only the pixels that see the light directly, unoccluded
  // from every sub-pixel position, could agree, and they are a small part of the image.
  EXPECT_GT(differing_pixels(*a, *b), a->rgb[0].size() / 2);
}

}  // namespace determinism_test
}  // namespace nimbus::e2e
