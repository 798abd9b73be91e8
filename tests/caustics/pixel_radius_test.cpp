// The per-pixel merge radius (pixel_radius.hpp): a pixel keeps the schedule's radius until its lookups
// have found more photons than the target, then shrinks so that its kernel would hold the target, never
// below the floor; the density is photons over searched area (times effective paths) on a decaying
// window, frozen between iterations; its state survives a save and a restore and rejects bad input.
#include <gtest/gtest.h>

#include <cmath>

#include "pixel_radius.hpp"
#include "state_bytes.hpp"

namespace nimbus::caustics {
namespace pixel_radius_test {

constexpr float kR = 0.01f, kNeff = 1e5f;

// A pixel whose lookups found photons at the density that puts `expected` of them in the kernel of radius
// kR with kNeff effective paths.
PixelRadius with_expected(double expected, size_t pixel = 3) {
  PixelRadius p;
  p.reset(8);
  p.found(pixel, uint32_t(expected), kR, kNeff);
  p.end_iteration();
  return p;
}

TEST(PixelRadius, KeepsTheScheduleRadiusUntilItsKernelHoldsMoreThanTheTarget) {
  PixelRadius p;
  p.reset(8);
  EXPECT_EQ(p.radius(3, kR, kNeff), kR);  // nothing found yet
  EXPECT_EQ(with_expected(kTargetPhotons).radius(3, kR, kNeff), kR);
  EXPECT_EQ(with_expected(0).radius(3, kR, kNeff), kR);
  EXPECT_EQ(with_expected(1000).radius(2, kR, kNeff), kR);  // another pixel
  EXPECT_EQ(p.radius(100, kR, kNeff), kR);                  // out of range: the schedule's
}

TEST(PixelRadius, ShrinksToHoldTheTargetAndNoFurtherThanTheFloor) {
  // Four times the target: half the radius holds the target.
  EXPECT_NEAR(with_expected(4 * kTargetPhotons).radius(3, kR, kNeff), kR / 2, 1e-6 * kR);
  // The density, not the count, decides: a radius twice as large expects four times the photons.
  EXPECT_NEAR(with_expected(kTargetPhotons).radius(3, 2 * kR, kNeff), kR, 1e-6 * kR);
  // And so do the effective paths.
  EXPECT_NEAR(with_expected(kTargetPhotons).radius(3, kR, 9 * kNeff), kR / 3, 1e-6 * kR);
  EXPECT_NEAR(with_expected(1e6).radius(3, kR, kNeff), kMinScale * kR, 1e-6 * kR);
}

TEST(PixelRadius, DensityIsFrozenDuringAPassAndFollowsRecentMaps) {
  PixelRadius p = with_expected(4 * kTargetPhotons);
  const float before = p.radius(3, kR, kNeff);
  p.found(3, 0, kR, kNeff);  // a later pass finds nothing here
  EXPECT_EQ(p.radius(3, kR, kNeff), before) << "changed before end_iteration()";
  p.end_iteration();
  // Window sums: photons 4K decay + 0, area 1 decay + 1 (in units of pi kR^2 kNeff).
  const double expected = 4 * kTargetPhotons * kWindowDecay / (kWindowDecay + 1);
  EXPECT_NEAR(p.radius(3, kR, kNeff), kR * std::sqrt(kTargetPhotons / expected), 1e-5 * kR);
  // Many empty passes later the old photons no longer count.
  for (int i = 0; i < 100; ++i) p.found(3, 0, kR, kNeff), p.end_iteration();
  EXPECT_EQ(p.radius(3, kR, kNeff), kR);
}

TEST(PixelRadius, StateRoundTripsAndRejectsBadInput) {
  PixelRadius p = with_expected(9 * kTargetPhotons);
  p.found(3, 5, kR, kNeff);  // pending sums are state too
  Bytes bytes;
  p.save(bytes);
  PixelRadius q;
  q.reset(8);
  ASSERT_TRUE(q.restore(bytes));
  EXPECT_EQ(q.radius(3, kR, kNeff), p.radius(3, kR, kNeff));
  p.end_iteration(), q.end_iteration();
  EXPECT_EQ(q.radius(3, kR, kNeff), p.radius(3, kR, kNeff));

  PixelRadius other;
  other.reset(9);  // another image size
  bytes.read = 0;
  EXPECT_FALSE(other.restore(bytes));
  EXPECT_EQ(other.radius(3, kR, kNeff), kR) << "a failed restore changed the state";

  // A negative density (a corrupt file) is refused.
  Bytes bad;
  PixelRadius empty;
  empty.reset(8);
  empty.save(bad);
  const size_t density_at = bad.data.size() - 8 * sizeof(float);
  const float negative = -1;
  std::memcpy(bad.data.data() + density_at, &negative, sizeof negative);
  PixelRadius r;
  r.reset(8);
  EXPECT_FALSE(r.restore(bad));
}

}  // namespace pixel_radius_test
}  // namespace nimbus::caustics
