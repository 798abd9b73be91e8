// Splats: per-worker buffers merged deterministically, normalised with the camera samples.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "film/film.hpp"

namespace nimbus {
namespace splat_test {

struct Splat {
  float fx, fy, v[3];
};

// Values spread over several binades and not dyadic, so a float accumulator or a different summation
// order would show up in the last bits.
std::vector<Splat> make_splats(uint32_t w, uint32_t h, size_t n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> pos_x(0.0f, float(w)), pos_y(0.0f, float(h)), unit(0.0f, 1.0f);
  std::uniform_int_distribution<int> octave(-10, 10);
  std::vector<Splat> splats(n);
  for (Splat &s : splats) {
    s.fx = pos_x(rng);
    s.fy = pos_y(rng);
    for (float &c : s.v) c = std::ldexp(unit(rng), octave(rng));
  }
  return splats;
}

// Camera samples, then one iteration's splats handed out by `worker_of`, twice.
std::vector<float> render(uint32_t workers, const std::vector<Splat> &splats, auto worker_of, bool reverse) {
  constexpr uint32_t kW = 8, kH = 6;
  Film film(kW, kH);
  film.set_worker_count(workers);
  const int32_t caustics = film.register_element("caustics", 3, Film::kSplat);
  film.request("caustics");
  EXPECT_TRUE(film.allocate().ok());
  for (int iteration = 0; iteration < 2; ++iteration) {
    for (uint32_t y = 0; y < kH; ++y) {
      for (uint32_t x = 0; x < kW; ++x) {
        const float v[3] = {0.1f * float(x + 1), 0.3f, 1.7f * float(y + 1)};
        film.accumulate(Film::kBeauty, x, y, v);
        film.accumulate(caustics, x, y, v);
      }
    }
    for (size_t k = 0; k < splats.size(); ++k) {
      const size_t i = reverse ? splats.size() - 1 - k : k;
      film.splat(worker_of(i), Film::kBeauty, splats[i].fx, splats[i].fy, splats[i].v);
      film.splat(worker_of(i), caustics, splats[i].fx, splats[i].fy, splats[i].v);
    }
    film.merge_splats();
    film.end_iteration();
  }
  std::vector<float> image = film.resolve(Film::kBeauty);
  const std::vector<float> c = film.resolve(caustics);
  EXPECT_EQ(image, c);
  return image;
}

TEST(FilmSplat, MergeIsIndependentOfHowSplatsWereSpreadOverWorkers) {
  const std::vector<Splat> splats = make_splats(8, 6, 4000, 7);
  const std::vector<float> one = render(
      1, splats, [](size_t) { return 0u; }, false);
  const std::vector<float> four = render(
      4, splats, [](size_t i) { return uint32_t(i * 2654435761u) >> 30; }, true);
  const std::vector<float> blocks = render(
      4, splats, [](size_t i) { return uint32_t(i / 1000); }, false);
  ASSERT_EQ(one.size(), 8u * 6u * 3u);
  // Bit-exact: a different thread count must not change a single pixel.
  EXPECT_EQ(one, four);
  EXPECT_EQ(one, blocks);
}

TEST(FilmSplat, SplatsShareTheIterationNormalisation) {
  Film film(3, 2);
  film.set_worker_count(2);
  const float a[3] = {4, 8, 12};
  const float b[3] = {2, 2, 2};
  film.splat(1, Film::kBeauty, 2.99f, 1.0f, a);  // pixel (2, 1)
  film.splat(0, Film::kBeauty, 2.0f, 1.99f, b);  // pixel (2, 1)
  film.merge_splats();
  film.end_iteration();
  film.end_iteration();
  const std::vector<float> image = film.resolve(Film::kBeauty);
  const size_t p = (1 * 3 + 2) * 3;
  EXPECT_EQ(image[p + 0], 3.0f);
  EXPECT_EQ(image[p + 1], 5.0f);
  EXPECT_EQ(image[p + 2], 7.0f);
  float rest = 0;
  for (size_t i = 0; i < image.size(); ++i) rest += (i / 3 == p / 3) ? 0.0f : image[i];
  EXPECT_EQ(rest, 0.0f);
}

TEST(FilmSplat, UnmergedSplatsAreNotInTheImage) {
  Film film(2, 2);
  const float v[3] = {1, 1, 1};
  film.splat(0, Film::kBeauty, 0.5f, 0.5f, v);
  film.end_iteration();
  EXPECT_EQ(film.resolve(Film::kBeauty)[0], 0.0f);
  film.merge_splats();
  EXPECT_EQ(film.resolve(Film::kBeauty)[0], 1.0f);
  film.merge_splats();  // merging twice must not add twice
  EXPECT_EQ(film.resolve(Film::kBeauty)[0], 1.0f);
}

TEST(FilmSplat, ChangingTheWorkerCountKeepsPendingSplats) {
  Film film(2, 2);
  film.set_worker_count(4);
  const float v[3] = {1, 1, 1};
  film.splat(3, Film::kBeauty, 1.5f, 1.5f, v);
  film.set_worker_count(2);
  film.end_iteration();
  EXPECT_EQ(film.resolve(Film::kBeauty)[9], 1.0f);
}

TEST(FilmSplat, BadSplatsAreDroppedAndNonFiniteOnesCounted) {
  Film film(4, 4);
  film.set_worker_count(2);
  const int32_t albedo = film.register_element("albedo", 3, Film::kAverage);
  film.request("albedo");
  ASSERT_TRUE(film.allocate().ok());
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float v[3] = {1, 1, 1};
  const float bad[3] = {1, nan, 1};
  film.splat(0, Film::kBeauty, 1.0f, 1.0f, bad);
  film.splat(0, Film::kBeauty, nan, 1.0f, v);
  film.splat(0, Film::kBeauty, 1.0f, std::numeric_limits<float>::infinity(), v);
  film.splat(0, Film::kBeauty, -0.5f, 1.0f, v);  // off the film: dropped, not an error
  film.splat(0, Film::kBeauty, 4.0f, 1.0f, v);
  film.splat(0, Film::kBeauty, 1.0f, 4.0f, v);
  film.splat(2, Film::kBeauty, 1.0f, 1.0f, v);  // no such worker
  film.splat(0, albedo, 1.0f, 1.0f, v);         // not a splat element
  film.merge_splats();
  film.end_iteration();
  EXPECT_EQ(film.nonfinite_count(), 3u);
  for (float c : film.resolve(Film::kBeauty)) EXPECT_EQ(c, 0.0f);
  for (float c : film.resolve(albedo)) EXPECT_EQ(c, 0.0f);
}

}  // namespace splat_test
}  // namespace nimbus
