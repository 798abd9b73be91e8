// core/math.hpp: atan2_fast (environment lookups) against libm's atan2 in double, over every octant,
// the axes, signed zeros and magnitudes from denormal to huge.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/math.hpp"

namespace nimbus {
namespace {

TEST(Atan2Fast, WithinTwoUlpsOfPiEverywhere) {
  double worst = 0;
  for (int i = 0; i < 200000; ++i) {
    const double angle = -M_PI + 2 * M_PI * (i + 0.5) / 200000;
    for (float r : {1e-30f, 1e-3f, 1.0f, 7.5e4f, 1e30f}) {
      const float x = float(r * std::cos(angle)), y = float(r * std::sin(angle));
      const double err = std::abs(double(atan2_fast(y, x)) - std::atan2(double(y), double(x)));
      worst = std::max(worst, err);
    }
  }
  EXPECT_LT(worst, 4e-7) << "worst error " << worst;
}

TEST(Atan2Fast, AxesZerosAndNanAsLibm) {
  for (float y : {0.0f, -0.0f, 1.0f, -1.0f})
    for (float x : {0.0f, -0.0f, 1.0f, -1.0f})
      EXPECT_NEAR(atan2_fast(y, x), std::atan2(y, x), 2e-7) << "y " << y << " x " << x;
  EXPECT_EQ(std::signbit(atan2_fast(-0.0f, 1.0f)), true);
  EXPECT_NEAR(atan2_fast(-0.0f, -1.0f), -kPi, 2e-7);
  EXPECT_TRUE(std::isnan(atan2_fast(std::numeric_limits<float>::quiet_NaN(), 1.0f)));
  EXPECT_NEAR(atan2_fast(1.0f, std::numeric_limits<float>::infinity()), 0.0f, 1e-30f);
}

}  // namespace
}  // namespace nimbus
