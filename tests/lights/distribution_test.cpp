// Distribution2D (environment maps, pixel filters): the cells it picks on a fine stratified grid of
// (u0, u1) occur at the rate its pdf states, zero-weight cells and rows never occur, and pdf(u, v) at the
// sampled point is the pdf the sample reported.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <nimbus/cpp/distribution.hpp>

namespace nimbus {
namespace distribution_test {

void expect_rates_match_pdf(const std::vector<float> &f, size_t w, size_t h) {
  const Distribution2D d(f, w, h);
  constexpr int kGrid = 1024;  // stratified: the rates are exact up to one stratum per cell boundary
  std::vector<double> count(w * h, 0);
  for (int i = 0; i < kGrid; ++i)
    for (int j = 0; j < kGrid; ++j) {
      float u = 0, v = 0, pdf = 0;
      size_t cell = 0;
      d.sample((float(j) + 0.5f) / kGrid, (float(i) + 0.5f) / kGrid, u, v, &pdf, &cell);
      ASSERT_GE(u, 0.0f);
      ASSERT_LT(u, 1.0f);
      ASSERT_GE(v, 0.0f);
      ASSERT_LT(v, 1.0f);
      ASSERT_EQ(cell, std::min(size_t(v * float(h)), h - 1) * w + std::min(size_t(u * float(w)), w - 1))
          << "the point lies in the cell reported";
      ASSERT_GT(pdf, 0.0f);
      ASSERT_EQ(pdf, d.pdf(u, v));
      ++count[cell];
    }
  double sum = 0;
  for (float x : f) sum += std::max(x, 0.0f);
  for (size_t c = 0; c < w * h; ++c) {
    const double rate = count[c] / (double(kGrid) * kGrid);
    const double expected = sum > 0 ? std::max(f[c], 0.0f) / sum : 1.0 / double(w * h);
    EXPECT_NEAR(d.cell_pdf(c) / double(w * h), expected, 1e-6 + 1e-5 * expected) << "cell " << c;
    // One stratum of 1/kGrid in each direction per cell edge.
    EXPECT_NEAR(rate, expected, 4.0 / kGrid * std::sqrt(expected) + 2e-6) << "cell " << c;
    if (expected == 0) {
      EXPECT_EQ(count[c], 0) << "a zero-weight cell is never sampled";
    }
  }
}

TEST(Distribution2D, SkewedCellsWithZeroRowAndColumn) {
  const size_t w = 8, h = 4;
  std::vector<float> f(w * h);
  for (size_t y = 0; y < h; ++y)
    for (size_t x = 0; x < w; ++x) f[y * w + x] = float((x + 1) * (x + 1) * (y + 2));
  for (size_t x = 0; x < w; ++x) f[1 * w + x] = 0;  // an empty row
  for (size_t y = 0; y < h; ++y) f[y * w + 5] = 0;  // an empty column
  f[3] = -2;                                        // negative counts as zero
  expect_rates_match_pdf(f, w, h);
}

TEST(Distribution2D, AllZeroIsUniform) { expect_rates_match_pdf(std::vector<float>(6 * 3, 0.0f), 6, 3); }

TEST(Distribution2D, DynamicRangeOfSixDecades) {
  const size_t w = 16, h = 8;
  std::vector<float> f(w * h, 1e-3f);
  f[5 * w + 9] = 1e3f;  // a sun-like hot spot
  expect_rates_match_pdf(f, w, h);
}

}  // namespace distribution_test
}  // namespace nimbus
