// Texture lookups: sRGB decoding of colour files (exact at texel centres, before filtering between them),
// float files and data as stored, periodic wrapping, orientation, and the per-point BSDFs built from them.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <cmath>

#include "materials/textured_materials.hpp"
#include "texture_fixtures.hpp"

namespace nimbus {
namespace lookup_test {

using texture_test::ScratchDir;
using texture_test::srgb8_to_linear;
using texture_test::texture_at;

constexpr uint8_t kA[3] = {188, 188, 188};
constexpr uint8_t kB[3] = {0, 64, 255};

Rgb linear(const uint8_t c[3]) {
  return {float(srgb8_to_linear(c[0])), float(srgb8_to_linear(c[1])), float(srgb8_to_linear(c[2]))};
}

void expect_rgb_near(const Rgb &got, const Rgb &want, float tol) {
  EXPECT_NEAR(got.x, want.x, tol);
  EXPECT_NEAR(got.y, want.y, tol);
  EXPECT_NEAR(got.z, want.z, tol);
}

TextureSet::Id add_ok(TextureSet &set, const std::string &path, TextureSet::Kind kind, int channels = 1) {
  auto id = set.add(texture_at(path), kind, channels);
  EXPECT_TRUE(id.ok()) << (id.ok() ? "" : id.error().message);
  return id.ok() ? id.value() : 0;
}

TEST(TextureLookup, SrgbCodeValuesDecodeExactly) {
  EXPECT_NEAR(srgb_to_linear(188 / 255.0f), 0.50289, 5e-5);
  for (int code = 0; code <= 255; ++code)
    EXPECT_NEAR(srgb_to_linear(float(code) / 255), srgb8_to_linear(code), 2e-6) << "code " << code;
}

TEST(TextureLookup, PngTexelCentresAreDecodedToLinear) {
  ScratchDir dir;
  texture_test::write_checker_png(dir.file("checker.png"), kA, kB);
  TextureSet set;
  const auto id = add_ok(set, dir.file("checker.png"), TextureSet::Kind::Color);
  // OIIO orientation: t = 0 is the top row; texel (i, j) is centred at ((i + 1/2) / 2, (j + 1/2) / 2).
  expect_rgb_near(set.rgb(id, {0.25f, 0.25f}), linear(kA), 1e-6f);
  expect_rgb_near(set.rgb(id, {0.75f, 0.25f}), linear(kB), 1e-6f);
  expect_rgb_near(set.rgb(id, {0.25f, 0.75f}), linear(kB), 1e-6f);
  expect_rgb_near(set.rgb(id, {0.75f, 0.75f}), linear(kA), 1e-6f);
  EXPECT_NEAR(set.rgb(id, {0.25f, 0.25f}).x, 0.50289f, 5e-5f);
}

TEST(TextureLookup, ColourIsFilteredAfterDecoding) {
  ScratchDir dir;
  texture_test::write_checker_png(dir.file("checker.png"), kA, kB);
  TextureSet set;
  const auto id = add_ok(set, dir.file("checker.png"), TextureSet::Kind::Color);
  // Half way between two texels: the mean of the linear values, not the decoded mean of the codes.
  expect_rgb_near(set.rgb(id, {0.5f, 0.25f}), (linear(kA) + linear(kB)) * 0.5f, 1e-5f);
  // A quarter of the way: weights 3/4 and 1/4.
  expect_rgb_near(set.rgb(id, {0.375f, 0.25f}), linear(kA) * 0.75f + linear(kB) * 0.25f, 1e-5f);
  // The centre of the checker: all four texels equally.
  expect_rgb_near(set.rgb(id, {0.5f, 0.5f}), (linear(kA) + linear(kB)) * 0.5f, 1e-5f);
}

TEST(TextureLookup, WrapsPeriodically) {
  ScratchDir dir;
  texture_test::write_checker_png(dir.file("checker.png"), kA, kB);
  TextureSet set;
  const auto id = add_ok(set, dir.file("checker.png"), TextureSet::Kind::Color);
  for (const Vec2f st :
       {Vec2f{1.25f, 0.25f}, Vec2f{-0.75f, 0.25f}, Vec2f{0.25f, 3.25f}, Vec2f{-1.75f, -0.75f}})
    expect_rgb_near(set.rgb(id, st), linear(kA), 1e-5f);
  // On the edge s = 0 the first and last columns blend.
  expect_rgb_near(set.rgb(id, {0.0f, 0.25f}), (linear(kA) + linear(kB)) * 0.5f, 1e-5f);
}

TEST(TextureLookup, ExrIsLinearAndFilteredBilinearly) {
  ScratchDir dir;
  const std::vector<float> ramp = {0.0f, 0.25f, 0.5f, 1.0f};  // a 4x1 roughness ramp
  texture_test::write_exr(dir.file("ramp.exr"), 4, 1, 1, ramp);
  TextureSet set;
  const auto data = add_ok(set, dir.file("ramp.exr"), TextureSet::Kind::Data);
  const auto colour = add_ok(set, dir.file("ramp.exr"), TextureSet::Kind::Color);
  for (int i = 0; i < 4; ++i) {
    const float s = (float(i) + 0.5f) / 4;
    EXPECT_NEAR(set.scalar(data, {s, 0.5f}), ramp[size_t(i)], 1e-6f) << "texel " << i;
    expect_rgb_near(set.rgb(colour, {s, 0.5f}), Rgb(ramp[size_t(i)]), 1e-6f);  // float files: no decoding
  }
  EXPECT_NEAR(set.scalar(data, {0.5f, 0.5f}), 0.375f, 1e-5f);   // between texels 1 and 2
  EXPECT_NEAR(set.scalar(data, {0.25f, 0.5f}), 0.125f, 1e-5f);  // between texels 0 and 1
}

TEST(TextureLookup, PngDataIsNotDecoded) {
  ScratchDir dir;
  texture_test::write_png8(dir.file("rough.png"), 1, 1, 1, {128});
  TextureSet set;
  const auto id = add_ok(set, dir.file("rough.png"), TextureSet::Kind::Data);
  EXPECT_NEAR(set.scalar(id, {0.3f, 0.6f}), 128 / 255.0f, 1e-6f);
}

TEST(TextureLookup, GreyAndAlphaFilesGiveGrey) {
  ScratchDir dir;
  texture_test::write_png8(dir.file("grey.png"), 1, 1, 1, {188});
  texture_test::write_png8(dir.file("grey_alpha.png"), 1, 1, 2, {188, 0});  // alpha 0 must not darken it
  texture_test::write_png8(dir.file("rgba.png"), 1, 1, 4, {188, 64, 0, 10});
  TextureSet set;
  const float l188 = float(srgb8_to_linear(188));
  expect_rgb_near(set.rgb(add_ok(set, dir.file("grey.png"), TextureSet::Kind::Color), {0.5f, 0.5f}),
                  Rgb(l188), 1e-6f);
  expect_rgb_near(set.rgb(add_ok(set, dir.file("grey_alpha.png"), TextureSet::Kind::Color), {0.5f, 0.5f}),
                  Rgb(l188), 1e-6f);
  expect_rgb_near(set.rgb(add_ok(set, dir.file("rgba.png"), TextureSet::Kind::Color), {0.5f, 0.5f}),
                  Rgb(l188, float(srgb8_to_linear(64)), 0), 1e-6f);
}

TEST(TextureLookup, GreyCheckerIsFilteredAfterDecoding) {
  // One channel: texels are packed differently from RGB, inside the image and across its edges.
  ScratchDir dir;
  texture_test::write_png8(dir.file("grey.png"), 3, 2, 1, {188, 0, 64, 0, 188, 255});
  TextureSet set;
  const auto id = add_ok(set, dir.file("grey.png"), TextureSet::Kind::Color);
  const auto lin = [](int code) { return float(srgb8_to_linear(code)); };
  const float mean4 = (lin(188) + lin(0) + lin(0) + lin(188)) / 4;
  expect_rgb_near(set.rgb(id, {1 / 3.0f, 0.5f}), Rgb(mean4), 1e-5f);  // inside
  expect_rgb_near(set.rgb(id, {2 / 3.0f, 0.5f}), Rgb((lin(0) + lin(64) + lin(188) + lin(255)) / 4), 1e-5f);
  expect_rgb_near(set.rgb(id, {0.0f, 0.25f}), Rgb((lin(188) + lin(64)) / 2), 1e-5f);  // wraps in s
  expect_rgb_near(set.rgb(id, {0.5f / 3, 0.75f}), Rgb(lin(0)), 1e-6f);                // a texel centre
}

TEST(TextureLookup, JpegIsSrgbAndHdrIsLinear) {
  ScratchDir dir;
  // A uniform image: JPEG's block transform keeps a flat block's value.
  std::vector<uint8_t> grey(8 * 8 * 3, 188);
  {
    auto out = OIIO::ImageOutput::create(dir.file("flat.jpg"));
    ASSERT_TRUE(out);
    OIIO::ImageSpec spec(8, 8, 3, OIIO::TypeDesc::UINT8);
    spec.attribute("CompressionQuality", 100);
    ASSERT_TRUE(out->open(dir.file("flat.jpg"), spec));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, grey.data()));
    ASSERT_TRUE(out->close());
  }
  {
    auto out = OIIO::ImageOutput::create(dir.file("flat.hdr"));
    ASSERT_TRUE(out);
    const std::vector<float> px(4 * 4 * 3, 2.0f);  // RGBE stores powers of two exactly
    ASSERT_TRUE(out->open(dir.file("flat.hdr"), OIIO::ImageSpec(4, 4, 3, OIIO::TypeDesc::FLOAT)));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, px.data()));
    ASSERT_TRUE(out->close());
  }
  TextureSet set;
  const Rgb jpg = set.rgb(add_ok(set, dir.file("flat.jpg"), TextureSet::Kind::Color), {0.4f, 0.6f});
  EXPECT_NEAR(jpg.x, srgb8_to_linear(188), srgb8_to_linear(189) - srgb8_to_linear(188));
  expect_rgb_near(set.rgb(add_ok(set, dir.file("flat.hdr"), TextureSet::Kind::Color), {0.4f, 0.6f}),
                  Rgb(2.0f), 1e-6f);
}

TEST(TextureLookup, AFileNamedTwiceIsOneTexture) {
  ScratchDir dir;
  texture_test::write_checker_png(dir.file("checker.png"), kA, kB);
  TextureSet set;
  const auto a = add_ok(set, dir.file("checker.png"), TextureSet::Kind::Color);
  EXPECT_EQ(add_ok(set, dir.file("checker.png"), TextureSet::Kind::Color), a);
  EXPECT_NE(add_ok(set, dir.file("checker.png"), TextureSet::Kind::Data), a);  // same file, other meaning
}

// Materials: v = 0 is the bottom row, uv_scale repeats, and the textured parameter replaces the constant.
TEST(TexturedMaterials, AlbedoTextureFollowsUvWithVUp) {
  ScratchDir dir;
  texture_test::write_checker_png(dir.file("checker.png"), kA, kB);
  MaterialDesc m;
  m.albedo_texture = texture_at(dir.file("checker.png"));
  auto built = TexturedMaterials::build({MaterialDesc{}, m});
  ASSERT_TRUE(built.ok()) << built.error().message;
  const TexturedMaterials &tm = *built.value();
  EXPECT_FALSE(tm.textured(0));
  EXPECT_TRUE(tm.textured(1));
  EXPECT_FALSE(tm.varies_lobes(1));
  EXPECT_FALSE(tm.has_normal_map(1));
  const Vec3f up{0, 0, 1};
  expect_rgb_near(tm.bsdf(1, {0.25f, 0.75f}).albedo(up), linear(kA), 1e-6f);  // top-left texel
  expect_rgb_near(tm.bsdf(1, {0.75f, 0.75f}).albedo(up), linear(kB), 1e-6f);  // top-right
  expect_rgb_near(tm.bsdf(1, {0.25f, 0.25f}).albedo(up), linear(kB), 1e-6f);  // bottom-left
}

TEST(TexturedMaterials, UvScaleRepeats) {
  ScratchDir dir;
  texture_test::write_checker_png(dir.file("checker.png"), kA, kB);
  MaterialDesc m;
  m.albedo_texture = texture_at(dir.file("checker.png"));
  m.uv_scale = {2, 4};
  auto built = TexturedMaterials::build({m});
  ASSERT_TRUE(built.ok()) << built.error().message;
  const Vec3f up{0, 0, 1};
  // u = 0.125 -> s = 0.25; v = 0.0625 -> t = 1 - 0.25 = 0.75: the bottom-left texel.
  expect_rgb_near(built.value()->bsdf(0, {0.125f, 0.0625f}).albedo(up), linear(kB), 1e-6f);
  expect_rgb_near(built.value()->bsdf(0, {0.625f, 0.3125f}).albedo(up), linear(kB), 1e-6f);  // next repeat
  expect_rgb_near(built.value()->bsdf(0, {0.375f, 0.0625f}).albedo(up), linear(kA), 1e-6f);
}

TEST(TexturedMaterials, RoughnessTextureSetsTheLobe) {
  ScratchDir dir;
  texture_test::write_exr(dir.file("ramp.exr"), 4, 1, 1, {0.0f, 0.25f, 0.5f, 1.0f});
  MaterialDesc m;
  m.type = MaterialType::Conductor;
  m.roughness = 0.9f;  // replaced
  m.roughness_texture = texture_at(dir.file("ramp.exr"));
  auto built = TexturedMaterials::build({m});
  ASSERT_TRUE(built.ok()) << built.error().message;
  const TexturedMaterials &tm = *built.value();
  EXPECT_TRUE(tm.varies_lobes(0));
  MaterialDesc smooth;
  smooth.type = MaterialType::Conductor;
  EXPECT_EQ(tm.bsdf(0, {0.125f, 0.5f}).lobes(), make_bsdf(smooth).lobes());
  EXPECT_EQ(tm.bsdf(0, {0.125f, 0.5f}).min_alpha(), 0.0f);            // roughness 0: a delta lobe
  EXPECT_NEAR(tm.bsdf(0, {0.625f, 0.5f}).min_alpha(), 0.25f, 1e-6f);  // alpha = roughness^2
  EXPECT_NEAR(tm.bsdf(0, {0.875f, 0.5f}).min_alpha(), 1.0f, 1e-6f);
}

TEST(TexturedMaterials, NothingIsOpenedWithoutTextures) {
  MaterialDesc rough;
  rough.type = MaterialType::Dielectric;
  rough.roughness = 0.3f;
  auto built = TexturedMaterials::build({MaterialDesc{}, rough});
  ASSERT_TRUE(built.ok());
  EXPECT_EQ(built.value(), nullptr);
}

}  // namespace lookup_test
}  // namespace nimbus
