// Filter importance sampling: offsets stay inside the filter's support, the weights average to 1 (so
// the film's per-pixel mean is the filtered estimate), and offsets are distributed like the filter.
#include <gtest/gtest.h>

#include <random>

#include "world/pixel_filter.hpp"

namespace nimbus {
namespace pixel_filter_test {

class PixelFilterTest : public ::testing::TestWithParam<FilterType> {};

TEST_P(PixelFilterTest, WeightsAverageToOneAndFollowTheFilter) {
  const PixelFilter f(GetParam());
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> U(0, 1);
  constexpr int kBins = 16, kN = 400000;
  std::vector<double> hist(kBins * kBins, 0);
  double wsum = 0;
  for (int i = 0; i < kN; ++i) {
    float w = 0;
    const Vec2f d = f.sample(U(rng), U(rng), w);
    ASSERT_LE(std::abs(d.x), f.radius());
    ASSERT_LE(std::abs(d.y), f.radius());
    ASSERT_TRUE(std::isfinite(w));
    wsum += w;
    const int bx = std::min(kBins - 1, int((d.x / f.radius() + 1) / 2 * kBins));
    const int by = std::min(kBins - 1, int((d.y / f.radius() + 1) / 2 * kBins));
    hist[by * kBins + bx] += w;
  }
  EXPECT_NEAR(wsum / kN, 1.0, 0.005);
  // The weighted histogram estimates the filter's integral over each bin.
  const float cell = 2 * f.radius() / kBins;
  for (int by = 0; by < kBins; ++by)
    for (int bx = 0; bx < kBins; ++bx) {
      double integral = 0;
      for (int sy = 0; sy < 8; ++sy)
        for (int sx = 0; sx < 8; ++sx)
          integral += f.evaluate(-f.radius() + (bx + (sx + 0.5f) / 8) * cell,
                                 -f.radius() + (by + (sy + 0.5f) / 8) * cell) *
                      sqr(cell / 8);
      EXPECT_NEAR(hist[by * kBins + bx] / kN, integral, 0.002 + 0.05 * integral) << bx << "," << by;
    }
}

INSTANTIATE_TEST_SUITE_P(Filters, PixelFilterTest,
                         ::testing::Values(FilterType::Box, FilterType::Gaussian,
                                           FilterType::BlackmanHarris));

}  // namespace pixel_filter_test
}  // namespace nimbus
