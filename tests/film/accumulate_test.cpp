// Accumulation and resolution: averages over iterations, non-finite samples, concurrent writers.
#include <gtest/gtest.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <limits>

#include "film/film.hpp"

namespace nimbus {
namespace accumulate_test {

TEST(FilmAccumulate, ResolveAveragesOverCompletedIterations) {
  Film film(4, 3);
  const int32_t depth = film.register_element("depth", 1, Film::kAverage);
  film.request("depth");
  ASSERT_TRUE(film.allocate().ok());
  // Iteration i adds (i, 2i, 3i) + pixel index: the mean over i = 1..4 is 2.5 * (1, 2, 3) + index.
  for (int i = 1; i <= 4; ++i) {
    for (uint32_t y = 0; y < 3; ++y) {
      for (uint32_t x = 0; x < 4; ++x) {
        const float idx = float(y * 4 + x);
        const float rgb[3] = {float(i) + idx, 2.0f * float(i) + idx, 3.0f * float(i) + idx};
        film.accumulate(Film::kBeauty, x, y, rgb);
        const float d = 10.0f * float(i);
        film.accumulate(depth, x, y, &d);
      }
    }
    film.end_iteration();
  }
  EXPECT_EQ(film.iterations(), 4u);
  const std::vector<float> beauty = film.resolve(Film::kBeauty);
  const std::vector<float> z = film.resolve(depth);
  ASSERT_EQ(beauty.size(), 4u * 3u * 3u);
  ASSERT_EQ(z.size(), 4u * 3u);
  for (size_t p = 0; p < 12; ++p) {
    EXPECT_FLOAT_EQ(beauty[p * 3 + 0], 2.5f + float(p));
    EXPECT_FLOAT_EQ(beauty[p * 3 + 1], 5.0f + float(p));
    EXPECT_FLOAT_EQ(beauty[p * 3 + 2], 7.5f + float(p));
    EXPECT_FLOAT_EQ(z[p], 25.0f);
  }
}

TEST(FilmAccumulate, ResolveBeforeAnyIterationIsBlackNotNaN) {
  Film film(2, 2);
  const float one[3] = {1, 1, 1};
  film.accumulate(Film::kBeauty, 0, 0, one);
  const std::vector<float> image = film.resolve(Film::kBeauty);
  ASSERT_EQ(image.size(), 12u);
  for (float v : image) EXPECT_EQ(v, 0.0f);
}

TEST(FilmAccumulate, ResumedIterationCountDividesTheSums) {
  Film film(1, 1);
  const float v[3] = {6, 6, 6};
  film.accumulate(Film::kBeauty, 0, 0, v);
  film.set_iterations(2);
  film.end_iteration();
  EXPECT_EQ(film.iterations(), 3u);
  EXPECT_EQ(film.resolve(Film::kBeauty)[0], 2.0f);
}

TEST(FilmAccumulate, NonFiniteSamplesAreCountedAndNeverReachTheFilm) {
  Film film(2, 1);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const float good[3] = {1, 2, 3};
  const float bad_r[3] = {nan, 0, 0};
  const float bad_g[3] = {0, inf, 0};
  const float bad_b[3] = {0, 0, -inf};
  film.accumulate(Film::kBeauty, 0, 0, good);
  film.accumulate(Film::kBeauty, 0, 0, bad_r);
  film.accumulate(Film::kBeauty, 0, 0, bad_g);
  film.accumulate(Film::kBeauty, 1, 0, bad_b);
  film.end_iteration();
  EXPECT_EQ(film.nonfinite_count(), 3u);
  const std::vector<float> image = film.resolve(Film::kBeauty);
  // A bad sample is dropped whole: its finite channels do not leak in either.
  EXPECT_EQ(image, (std::vector<float>{1, 2, 3, 0, 0, 0}));
}

TEST(FilmAccumulate, InactiveElementsAndOutOfRangePixelsAreIgnored) {
  Film film(2, 2);
  const int32_t albedo = film.register_element("albedo", 3, Film::kAverage);
  ASSERT_TRUE(film.allocate().ok());
  const size_t bytes = film.allocated_bytes();
  const float v[3] = {1, 1, 1};
  film.accumulate(albedo, 0, 0, v);
  film.accumulate(Film::kBeauty, 2, 0, v);
  film.accumulate(Film::kBeauty, 0, 2, v);
  film.accumulate(42, 0, 0, v);
  film.accumulate(Film::kInvalid, 0, 0, v);
  film.end_iteration();
  EXPECT_FALSE(film.is_active(albedo));
  EXPECT_TRUE(film.resolve(albedo).empty());
  EXPECT_EQ(film.allocated_bytes(), bytes);
  for (float c : film.resolve(Film::kBeauty)) EXPECT_EQ(c, 0.0f);
}

TEST(FilmAccumulate, ConcurrentWritersOnDisjointPixels) {
  constexpr uint32_t kW = 61, kH = 47, kIterations = 8;
  Film film(kW, kH);
  for (uint32_t i = 0; i < kIterations; ++i) {
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, kH, 1), [&](const tbb::blocked_range<uint32_t> &rows) {
      for (uint32_t y = rows.begin(); y < rows.end(); ++y) {
        for (uint32_t x = 0; x < kW; ++x) {
          const float v[3] = {float(x), float(y), float(i)};
          film.accumulate(Film::kBeauty, x, y, v);
        }
      }
    });
    film.end_iteration();
  }
  const std::vector<float> image = film.resolve(Film::kBeauty);
  for (uint32_t y = 0; y < kH; ++y) {
    for (uint32_t x = 0; x < kW; ++x) {
      const float *p = &image[(size_t(y) * kW + x) * 3];
      ASSERT_EQ(p[0], float(x));
      ASSERT_EQ(p[1], float(y));
      ASSERT_EQ(p[2], 3.5f);
    }
  }
}

}  // namespace accumulate_test
}  // namespace nimbus
