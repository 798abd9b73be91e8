// The element registry: names, shapes, requests, and "no request, no buffer".
#include <gtest/gtest.h>

#include "film/film.hpp"

namespace nimbus {
namespace elements_test {

TEST(FilmElements, BeautyIsAlwaysRegisteredAndActive) {
  Film film(8, 8);
  EXPECT_TRUE(film.is_active(Film::kBeauty));
  EXPECT_EQ(film.element_name(Film::kBeauty), "beauty");
  EXPECT_EQ(film.element_channels(Film::kBeauty), 3u);
  EXPECT_EQ(film.register_element("beauty", 3, Film::kAverage), Film::kBeauty);
  EXPECT_EQ(film.register_element("beauty", 1, Film::kAverage), Film::kInvalid);
  EXPECT_EQ(film.active_elements(), std::vector<int32_t>{Film::kBeauty});
}

TEST(FilmElements, RegistrationValidatesNameChannelsAndFlags) {
  Film film(8, 8);
  const int32_t albedo = film.register_element("albedo", 3, Film::kAverage);
  EXPECT_GE(albedo, 1);
  EXPECT_EQ(film.register_element("albedo", 3, Film::kAverage), albedo);
  EXPECT_EQ(film.register_element("albedo", 3, Film::kSplat), albedo) << "flags merge, shape is channels";
  EXPECT_EQ(film.register_element("albedo", 1, Film::kAverage), Film::kInvalid);
  EXPECT_GE(film.register_element("lightmix.key_light", 3, Film::kSplat), 1);
  EXPECT_GE(film.register_element("depth", 1, Film::kAverage), 1);
  EXPECT_GE(film.register_element("aov_2", 1, Film::kAverage), 1);
  for (const char *bad : {"", "Albedo", "al bedo", "albedo-1", ".albedo", "albedo.", "lightmix..key", "é"}) {
    EXPECT_EQ(film.register_element(bad, 3, Film::kAverage), Film::kInvalid) << '"' << bad << '"';
  }
  for (uint32_t channels : {0u, 2u, 4u}) EXPECT_EQ(film.register_element("n", channels, 0), Film::kInvalid);
  EXPECT_EQ(film.register_element("n", 3, 2u), Film::kInvalid);
  EXPECT_EQ(film.element_name(albedo), "albedo");
}

TEST(FilmElements, UnrequestedElementsAllocateNoMemory) {
  constexpr uint32_t kW = 64, kH = 32;
  Film film(kW, kH);
  film.set_worker_count(4);
  const int32_t albedo = film.register_element("albedo", 3, Film::kAverage);
  const int32_t depth = film.register_element("depth", 1, Film::kAverage);
  const int32_t caustics = film.register_element("caustics", 3, Film::kSplat);
  const size_t beauty_only = film.allocated_bytes();
  EXPECT_GE(beauty_only, size_t(kW) * kH * 3 * sizeof(double));

  ASSERT_TRUE(film.allocate().ok());
  EXPECT_EQ(film.allocated_bytes(), beauty_only);
  // Work aimed at unrequested elements must not allocate either.
  const float v[3] = {1, 1, 1};
  film.accumulate(albedo, 1, 1, v);
  film.splat(0, caustics, 1.5f, 1.5f, v);
  film.merge_splats();
  EXPECT_EQ(film.allocated_bytes(), beauty_only);
  EXPECT_FALSE(film.is_active(albedo));
  EXPECT_FALSE(film.is_active(depth));
  EXPECT_FALSE(film.is_active(caustics));

  film.request("depth");
  ASSERT_TRUE(film.allocate().ok());
  EXPECT_TRUE(film.is_active(depth));
  EXPECT_FALSE(film.is_active(albedo));
  EXPECT_EQ(film.allocated_bytes(), beauty_only + size_t(kW) * kH * 1 * sizeof(double));
  EXPECT_EQ(film.active_elements(), (std::vector<int32_t>{Film::kBeauty, depth}));
}

TEST(FilmElements, SplatBuffersAreAllocatedOnlyByWorkersThatSplat) {
  constexpr uint32_t kW = 16, kH = 16;
  Film film(kW, kH);
  film.set_worker_count(8);
  const int32_t caustics = film.register_element("caustics", 3, Film::kSplat);
  film.request("caustics");
  ASSERT_TRUE(film.allocate().ok());
  const size_t before = film.allocated_bytes();
  const float v[3] = {1, 2, 3};
  film.splat(5, caustics, 3.0f, 4.0f, v);
  film.splat(5, caustics, 3.0f, 4.0f, v);
  EXPECT_EQ(film.allocated_bytes(), before + size_t(kW) * kH * 3 * sizeof(double));
}

TEST(FilmElements, UnknownRequestNamesTheAvailableElements) {
  Film film(4, 4);
  film.register_element("depth", 1, Film::kAverage);
  film.register_element("albedo", 3, Film::kAverage);
  film.request("albedo");
  film.request("albdo");
  const size_t before = film.allocated_bytes();
  const Status status = film.allocate();
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.error().message, "unknown render element 'albdo' (available: albedo, beauty, depth)");
  // A failed allocate allocates nothing, not even the valid requests.
  EXPECT_EQ(film.allocated_bytes(), before);
  EXPECT_FALSE(film.is_active(1));
}

TEST(FilmElements, SeveralUnknownRequestsAreAllNamed) {
  Film film(4, 4);
  film.request("normal");
  film.request("normal");
  film.request("uv");
  const Status status = film.allocate();
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.error().message, "unknown render elements 'normal', 'uv' (available: beauty)");
}

TEST(FilmElements, RequestingBeautyIsHarmless) {
  Film film(4, 4);
  film.request("beauty");
  EXPECT_TRUE(film.allocate().ok());
  EXPECT_EQ(film.active_elements(), std::vector<int32_t>{Film::kBeauty});
}

}  // namespace elements_test
}  // namespace nimbus
