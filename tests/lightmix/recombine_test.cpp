// The recombination: beauty' = Σ scale·tint·layer + (beauty − Σ layer), on a synthetic image read back
// from an EXR, and the --set syntax.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>

#include "e2e_support.hpp"
#include "film/lightmix_recombine.hpp"
#include "lightmix_fixture.hpp"

namespace nimbus {
namespace recombine_test {

using e2e::TestDir;
using test::LightMixImage;

struct Loaded {
  LightMixImage source;
  ImageLayers image;
};

Loaded load(const TestDir &dir) {
  Loaded l{test::make_lightmix_image(), {}};
  const std::string path = dir.file("in.exr");
  EXPECT_TRUE(test::write_lightmix_exr(path, l.source).ok());
  auto read = read_exr_layers(path);
  EXPECT_TRUE(read.ok());
  if (read) l.image = std::move(read.value());
  return l;
}

std::vector<LightMixSetting> settings(const std::vector<std::string> &texts) {
  std::vector<LightMixSetting> out;
  for (const std::string &t : texts) {
    auto s = parse_lightmix_setting(t);
    EXPECT_TRUE(s.ok()) << t << ": " << s.error().message;
    if (s) out.push_back(s.value());
  }
  return out;
}

void expect_close(float actual, double expected, const std::string &what) {
  EXPECT_NEAR(actual, expected, 1e-6 * std::max(1.0, std::abs(expected))) << what;
}

TEST(Recombine, GroupsAreTheLightMixLayers) {
  TestDir dir;
  const Loaded l = load(dir);
  EXPECT_EQ(lightmix_groups(l.image), (std::vector<std::string>{"fill", "key"}));
}

TEST(Recombine, ScaleOneEverywhereGivesBeautyBackBitForBit) {
  TestDir dir;
  Loaded l = load(dir);
  for (const auto &set : {std::vector<std::string>{}, std::vector<std::string>{"key=1", "fill=1,1,1,1"}}) {
    ImageLayers image = l.image;
    const auto mix = recombine_lightmix(image, settings(set));
    ASSERT_TRUE(mix.ok()) << mix.error().message;
    EXPECT_EQ(mix.value(), "fill=1;key=1");
    for (const std::string layer : {"beauty", "lightmix.key", "lightmix.fill", "albedo", "depth"}) {
      const auto &a = image.layers.at(layer).data, &b = l.image.layers.at(layer).data;
      for (size_t i = 0; i < a.size(); ++i)
        ASSERT_EQ(std::bit_cast<uint32_t>(a[i]), std::bit_cast<uint32_t>(b[i])) << layer << "[" << i << "]";
    }
  }
}

TEST(Recombine, ScaleZeroEverywhereLeavesTheResidual) {
  TestDir dir;
  Loaded l = load(dir);
  const auto mix = recombine_lightmix(l.image, settings({"key=0", "fill=0"}));
  ASSERT_TRUE(mix.ok()) << mix.error().message;
  EXPECT_EQ(mix.value(), "fill=0;key=0");
  const LightMixImage &s = l.source;
  const auto &beauty = l.image.layers.at("beauty").data;
  for (size_t i = 0; i < beauty.size(); ++i) {
    const double residual = double(s.beauty[i]) - (double(s.key[i]) + double(s.fill[i]));
    EXPECT_GT(residual, -1e-6);  // the fixture's residual is in [0, 1e-3]
    EXPECT_LT(residual, 1.1e-3);
    EXPECT_EQ(beauty[i], static_cast<float>(residual)) << i;
  }
  for (float v : l.image.layers.at("lightmix.key").data) EXPECT_EQ(v, 0.0f);
  // The channel planes follow the layers.
  EXPECT_EQ(l.image.channels.at("G")[3], beauty[3 * 3 + 1]);
  EXPECT_EQ(l.image.channels.at("lightmix.fill.B")[2], 0.0f);
}

TEST(Recombine, TintScalesEachChannelOfItsGroupOnly) {
  TestDir dir;
  Loaded l = load(dir);
  const auto mix = recombine_lightmix(l.image, settings({"lightmix.key=2,1,0.5,0"}));
  ASSERT_TRUE(mix.ok()) << mix.error().message;
  EXPECT_EQ(mix.value(), "fill=1;key=2,1,0.5,0");
  const LightMixImage &s = l.source;
  const double gain[3] = {2, 1, 0};
  const auto &beauty = l.image.layers.at("beauty").data, &key = l.image.layers.at("lightmix.key").data;
  for (size_t i = 0; i < beauty.size(); ++i) {
    const double k = s.key[i], f = s.fill[i], residual = double(s.beauty[i]) - (k + f);
    expect_close(beauty[i], gain[i % 3] * k + f + residual, "beauty[" + std::to_string(i) + "]");
    expect_close(key[i], gain[i % 3] * k, "key[" + std::to_string(i) + "]");
  }
  EXPECT_EQ(l.image.layers.at("lightmix.fill").data, s.fill);
  EXPECT_EQ(l.image.layers.at("albedo").data, s.albedo);
  EXPECT_EQ(l.image.layers.at("depth").data, s.depth);
}

TEST(Recombine, MixingTheResultAgainComposes) {
  TestDir dir;
  Loaded once = load(dir), twice = load(dir);
  ASSERT_TRUE(recombine_lightmix(once.image, settings({"key=6"})).ok());
  ASSERT_TRUE(recombine_lightmix(twice.image, settings({"key=2"})).ok());
  ASSERT_TRUE(recombine_lightmix(twice.image, settings({"key=3"})).ok());
  const auto &a = once.image.layers.at("beauty").data, &b = twice.image.layers.at("beauty").data;
  for (size_t i = 0; i < a.size(); ++i) expect_close(b[i], a[i], "beauty[" + std::to_string(i) + "]");
}

TEST(Recombine, ErrorsLeaveTheImageUnchanged) {
  TestDir dir;
  Loaded l = load(dir);
  const ImageLayers before = l.image;
  auto mix = recombine_lightmix(l.image, settings({"rim=2"}));
  ASSERT_FALSE(mix.ok());
  EXPECT_EQ(mix.error().message, "unknown light group 'rim' (available: fill, key)");
  mix = recombine_lightmix(l.image, settings({"key=2", "key=3"}));
  ASSERT_FALSE(mix.ok());
  EXPECT_NE(mix.error().message.find("'key' is set more than once"), std::string::npos);
  EXPECT_EQ(l.image.layers.at("beauty").data, before.layers.at("beauty").data);

  const std::string plain = dir.file("plain.exr");
  ASSERT_TRUE(test::write_lightmix_exr(plain, l.source, false).ok());
  auto image = read_exr_layers(plain);
  ASSERT_TRUE(image.ok());
  mix = recombine_lightmix(image.value(), {});
  ASSERT_FALSE(mix.ok());
  EXPECT_NE(mix.error().message.find("no LightMix layers"), std::string::npos) << mix.error().message;
}

TEST(LightMixSetting, ParsesScaleAndTint) {
  auto s = parse_lightmix_setting("key=2.5");
  ASSERT_TRUE(s.ok());
  EXPECT_EQ(s->group, "key");
  EXPECT_EQ(s->scale, 2.5f);
  EXPECT_EQ(s->color, (std::array<float, 3>{1, 1, 1}));
  s = parse_lightmix_setting("lightmix.sun_2=0.5,1,0.8,0");
  ASSERT_TRUE(s.ok());
  EXPECT_EQ(s->group, "sun_2");
  EXPECT_EQ(s->scale, 0.5f);
  EXPECT_EQ(s->color, (std::array<float, 3>{1, 0.8f, 0}));
}

TEST(LightMixSetting, MalformedSettingsSayWhatIsWrong) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"key", "no '='"},
      {"=2", "no group name"},
      {"key=", "'' is not a number"},
      {"key=bright", "'bright' is not a number"},
      {"key=2x", "'2x' is not a number"},
      {"key=1,2", "2 numbers"},
      {"key=1,1,1,1,1", "5 numbers"},
      {"key=-1", "'-1' is not finite and >= 0"},
      {"key=inf", "'inf' is not finite and >= 0"},
      {"key=1,1,,1", "'' is not a number"},
  };
  for (const auto &[text, reason] : cases) {
    const auto s = parse_lightmix_setting(text);
    ASSERT_FALSE(s.ok()) << text;
    EXPECT_NE(s.error().message.find("'" + text + "'"), std::string::npos) << s.error().message;
    EXPECT_NE(s.error().message.find(reason), std::string::npos) << s.error().message;
  }
}

}  // namespace recombine_test
}  // namespace nimbus
