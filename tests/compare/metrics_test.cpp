// The metrics against hand-computed values, non-finite handling, and the heatmap's colours.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "e2e_support.hpp"
#include "film/image_compare.hpp"

namespace nimbus {
namespace metrics_test {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

ImageLayer rgb(std::vector<float> data) { return {{"R", "G", "B"}, std::move(data)}; }
ImageLayer constant(size_t pixels, float v) { return rgb(std::vector<float>(pixels * 3, v)); }

TEST(Metrics, IdenticalImagesHaveZeroError) {
  const ImageLayer a = rgb({0.1f, 2, 30, 0, 0, 0});
  const auto m = compare_images(a, a, 2, 1);
  ASSERT_TRUE(m.ok());
  EXPECT_EQ(m->rmse, 0);
  EXPECT_EQ(m->relmse, 0);
  EXPECT_EQ(m->mape, 0);
  EXPECT_EQ(m->relmse_luminance, 0);
  EXPECT_EQ(m->compared_pixels, 2u);
}

TEST(Metrics, UniformTenPercentError) {
  // t = 1.1 against r = 1 everywhere: every formula reduces to one term.
  const auto m = compare_images(constant(12, 1.1f), constant(12, 1.0f), 4, 3);
  ASSERT_TRUE(m.ok());
  const double d = double(1.1f) - 1.0;
  EXPECT_NEAR(m->rmse, d, 1e-12);
  EXPECT_NEAR(m->relmse, d * d / 1.01, 1e-12);
  EXPECT_NEAR(m->mape, d / 1.01, 1e-12);
  // The Rec. 709 weights sum to 1, so luminance sees the same error.
  EXPECT_NEAR(m->relmse_luminance, d * d / 1.01, 1e-9);
  EXPECT_EQ(m->pixels, 12u);
  EXPECT_EQ(m->compared_pixels, 12u);
}

TEST(Metrics, MixedErrorsMatchTheDefinitions) {
  // Two pixels, errors in different channels and at different reference levels.
  const ImageLayer t = rgb({1, 0, 3, 0.5f, 0.5f, 0.5f});
  const ImageLayer r = rgb({1, 1, 2, 0, 0.5f, 0.25f});
  const auto m = compare_images(t, r, 2, 1);
  ASSERT_TRUE(m.ok());
  const double eps = kCompareEpsilon;
  const double sq[6] = {0, 1, 1, 0.25, 0, 0.0625};
  const double ref[6] = {1, 1, 2, 0, 0.5, 0.25};
  double rmse = 0, relmse = 0, mape = 0;
  for (int i = 0; i < 6; ++i) {
    rmse += sq[i];
    relmse += sq[i] / (ref[i] * ref[i] + eps);
    mape += std::sqrt(sq[i]) / (ref[i] + eps);
  }
  EXPECT_NEAR(m->rmse, std::sqrt(rmse / 6), 1e-12);
  EXPECT_NEAR(m->relmse, relmse / 6, 1e-12);
  EXPECT_NEAR(m->mape, mape / 6, 1e-12);
  auto y = [](double r, double g, double b) { return 0.2126 * r + 0.7152 * g + 0.0722 * b; };
  const double yt[2] = {y(1, 0, 3), y(0.5, 0.5, 0.5)}, yr[2] = {y(1, 1, 2), y(0, 0.5, 0.25)};
  double rel_y = 0;
  for (int p = 0; p < 2; ++p) rel_y += (yt[p] - yr[p]) * (yt[p] - yr[p]) / (yr[p] * yr[p] + eps);
  EXPECT_NEAR(m->relmse_luminance, rel_y / 2, 1e-9);
}

TEST(Metrics, NonFinitePixelsAreCountedAndLeftOut) {
  ImageLayer t = constant(4, 2), r = constant(4, 1);
  t.data[1] = kNaN;   // pixel 0
  t.data[9] = -kInf;  // pixel 3
  r.data[5] = kInf;   // pixel 1
  const auto m = compare_images(t, r, 2, 2);
  ASSERT_TRUE(m.ok());
  EXPECT_EQ(m->nonfinite_test, 2u);
  EXPECT_EQ(m->nonfinite_reference, 1u);
  EXPECT_EQ(m->compared_pixels, 1u);  // only pixel 2 is finite in both
  EXPECT_NEAR(m->rmse, 1, 1e-12);
  EXPECT_NEAR(m->relmse, 1 / 1.01, 1e-12);
}

TEST(Metrics, NothingComparableGivesNaNMetrics) {
  const auto m = compare_images(constant(1, kNaN), constant(1, 1), 1, 1);
  ASSERT_TRUE(m.ok());
  EXPECT_TRUE(std::isnan(m->rmse));
  EXPECT_TRUE(std::isnan(m->relmse_luminance));
  EXPECT_EQ(m->nonfinite_test, 1u);
}

TEST(Metrics, SingleChannelLayers) {
  const ImageLayer t{{"depth.Y"}, {2, 4}}, r{{"depth.Y"}, {1, 4}};
  const auto m = compare_images(t, r, 2, 1);
  ASSERT_TRUE(m.ok());
  EXPECT_NEAR(m->rmse, std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(m->relmse_luminance, (1 / 1.01) / 2, 1e-12);
}

TEST(Metrics, ChannelCountMismatchIsAnError) {
  const auto m = compare_images(constant(1, 1), ImageLayer{{"Y"}, {1}}, 1, 1);
  ASSERT_FALSE(m.ok());
  EXPECT_NE(m.error().message.find("3 in TEST, 1 in REF"), std::string::npos) << m.error().message;
}

TEST(Metrics, RelativeErrorMapIsPerPixelChannelMean) {
  ImageLayer t = rgb({2, 1, 1, 1, 1, 1}), r = rgb({1, 1, 1, 1, 1, 1});
  t.data[4] = kNaN;
  const std::vector<float> e = relative_error_map(t, r, 2, 1);
  ASSERT_EQ(e.size(), 2u);
  EXPECT_NEAR(e[0], (1 / 1.01) / 3, 1e-7);
  EXPECT_TRUE(std::isnan(e[1]));
}

std::vector<uint8_t> read_png(const std::string &path, int &w, int &h) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) return {};
  w = in->spec().width;
  h = in->spec().height;
  std::vector<uint8_t> px(size_t(w) * h * 3);
  in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, px.data());
  in->close();
  return px;
}

TEST(Heatmap, ViridisOnALogScaleWithMagentaForNonFinite) {
  e2e::TestDir dir;
  const std::string path = dir.file("heat.png");
  // Zero, the bottom of the scale, the middle, the top, above the top, NaN.
  const std::vector<float> error = {0, 1e-4f, std::pow(10.0f, -1.5f), 10, 1e6f, kNaN};
  const Status s = write_error_heatmap(path, error, 3, 2);
  ASSERT_TRUE(s.ok()) << s.error().message;
  int w = 0, h = 0;
  const std::vector<uint8_t> px = read_png(path, w, h);
  ASSERT_EQ(w, 3);
  ASSERT_EQ(h, 2);
  auto at = [&](int p) { return std::vector<int>{px[p * 3], px[p * 3 + 1], px[p * 3 + 2]}; };
  const std::vector<int> purple = {68, 1, 84}, teal = {33, 145, 140}, yellow = {253, 231, 37};
  EXPECT_EQ(at(0), purple);
  EXPECT_EQ(at(1), purple);
  EXPECT_EQ(at(2), teal);
  EXPECT_EQ(at(3), yellow);
  EXPECT_EQ(at(4), yellow);
  EXPECT_EQ(at(5), (std::vector<int>{255, 0, 255}));
  EXPECT_NE(heatmap_legend().find("<= 1e-4"), std::string::npos) << heatmap_legend();
}

}  // namespace metrics_test
}  // namespace nimbus
