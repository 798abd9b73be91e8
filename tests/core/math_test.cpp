// core/math.hpp: atan2_fast (environment lookups) against libm's atan2 in double, over every octant,
// the axes, signed zeros and magnitudes from denormal to huge; next_float against std::nextafter;
// cos_sin_quarter (the concentric disk mapping's angle, sampling.hpp) against cos and sin in double.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include <nimbus/cpp/math.hpp>
#include <nimbus/cpp/sampling.hpp>

namespace nimbus {
namespace math_test {

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

// next_float equals std::nextafter towards +-infinity, bit for bit, for every finite float: random bit
// patterns over all exponents, and the edges (signed zeros, smallest subnormals, the largest float, the
// normal/subnormal boundary, powers of two where the ulp changes).
TEST(NextFloat, AsNextafterForEveryFiniteFloat) {
  std::mt19937 g(3);
  std::vector<float> values = {0.0f,
                               -0.0f,
                               0x1p-149f,
                               -0x1p-149f,
                               0x1p-126f,
                               -0x1p-126f,
                               std::numeric_limits<float>::max(),
                               -std::numeric_limits<float>::max(),
                               1.0f,
                               -1.0f,
                               0x1p24f,
                               -0x1p-24f,
                               1e4f,
                               -3.5e-20f};
  while (values.size() < 200000) {
    const float v = std::bit_cast<float>(uint32_t(g()));
    if (std::isfinite(v)) values.push_back(v);
  }
  for (float v : values)
    for (bool up : {true, false}) {
      const float want = std::nextafter(v, up ? kInfinity : -kInfinity);
      ASSERT_EQ(std::bit_cast<uint32_t>(next_float(v, up)), std::bit_cast<uint32_t>(want)) << v << " " << up;
    }
  EXPECT_EQ(next_float(kInfinity, true), kInfinity);
  EXPECT_TRUE(std::isnan(next_float(std::numeric_limits<float>::quiet_NaN(), true)));
}

// Within 1.5 ulps of cos and sin over the whole eighth of a turn either side of zero, both ends included,
// and the concentric mapping's points on a fine grid within the unit disk and on the polar formula's
// radius and angle.
TEST(CosSinQuarter, WithinOneAndAHalfUlpsOverAQuarterTurn) {
  const auto ulps = [](float got, double want) {
    const float w = float(want);
    const double ulp = double(std::nextafter(std::abs(w), kInfinity)) - std::abs(w);
    return std::abs(double(got) - want) / ulp;
  };
  double worst_cos = 0, worst_sin = 0;
  const int n = 400000;
  for (int i = 0; i <= n; ++i) {
    const float a = std::clamp(float(-M_PI / 4 + M_PI / 2 * i / n), -kPi / 4, kPi / 4);
    const Vec2f cs = cos_sin_quarter(a);
    worst_cos = std::max(worst_cos, ulps(cs.x, std::cos(double(a))));
    if (a != 0) worst_sin = std::max(worst_sin, ulps(cs.y, std::sin(double(a))));
  }
  EXPECT_LT(worst_cos, 1.5);
  EXPECT_LT(worst_sin, 1.5);
  EXPECT_EQ(cos_sin_quarter(0).x, 1.0f);
  EXPECT_EQ(cos_sin_quarter(0).y, 0.0f);
  for (int i = 0; i < 512; ++i)
    for (int j = 0; j < 512; ++j) {
      const float u0 = (i + 0.5f) / 512, u1 = (j + 0.5f) / 512;
      const Vec2f d = sample_uniform_disk_concentric(u0, u1);
      const double ox = 2.0 * u0 - 1, oy = 2.0 * u1 - 1;
      const double r = std::abs(ox) > std::abs(oy) ? ox : oy;
      const double theta =
          std::abs(ox) > std::abs(oy) ? M_PI / 4 * (oy / ox) : M_PI / 2 - M_PI / 4 * (ox / oy);
      ASSERT_LE(double(d.x) * d.x + double(d.y) * d.y, 1.0) << u0 << " " << u1;
      ASSERT_NEAR(d.x, r * std::cos(theta), 4e-7) << u0 << " " << u1;
      ASSERT_NEAR(d.y, r * std::sin(theta), 4e-7) << u0 << " " << u1;
    }
}

}  // namespace math_test
}  // namespace nimbus
