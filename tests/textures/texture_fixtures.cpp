#include "texture_fixtures.hpp"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <fstream>

namespace nimbus::texture_test {

namespace {

void write_image(const std::string &path, int width, int height, int channels, OIIO::TypeDesc type,
                 const void *pixels) {
  auto out = OIIO::ImageOutput::create(path);
  ASSERT_TRUE(out) << OIIO::geterror();
  OIIO::ImageSpec spec(width, height, channels, type);
  spec.attribute("oiio:UnassociatedAlpha", 1);  // write colour as given, not divided by alpha
  ASSERT_TRUE(out->open(path, spec)) << out->geterror();
  ASSERT_TRUE(out->write_image(type, pixels)) << out->geterror();
  ASSERT_TRUE(out->close()) << out->geterror();
}

}  // namespace

ScratchDir::ScratchDir() {
  const auto *info = ::testing::UnitTest::GetInstance()->current_test_info();
  path_ = std::filesystem::temp_directory_path() /
          ("nimbus-textures-" + std::to_string(::getpid()) + "-" + (info ? info->name() : "test"));
  std::filesystem::remove_all(path_);
  std::filesystem::create_directories(path_);
}

ScratchDir::~ScratchDir() {
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

void write_png8(const std::string &path, int width, int height, int channels,
                const std::vector<uint8_t> &pixels) {
  ASSERT_EQ(pixels.size(), size_t(width) * height * channels);
  write_image(path, width, height, channels, OIIO::TypeDesc::UINT8, pixels.data());
}

void write_exr(const std::string &path, int width, int height, int channels,
               const std::vector<float> &pixels) {
  ASSERT_EQ(pixels.size(), size_t(width) * height * channels);
  write_image(path, width, height, channels, OIIO::TypeDesc::FLOAT, pixels.data());
}

void write_text(const std::string &path, const std::string &text) {
  std::ofstream(path, std::ios::binary) << text;
}

void write_checker_png(const std::string &path, const uint8_t a[3], const uint8_t b[3]) {
  std::vector<uint8_t> px;
  for (const uint8_t *c : {a, b, b, a}) px.insert(px.end(), c, c + 3);
  write_png8(path, 2, 2, 3, px);
}

TextureDesc texture_at(const std::string &path) {
  TextureDesc t;
  t.path = path;
  t.key = "materials.m.albedo.texture";
  t.where = {"scene.yaml", 7, 22};
  return t;
}

::testing::AssertionResult has_substr(const std::string &text, const std::string &part) {
  if (text.find(part) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "'" << text << "' does not contain '" << part << "'";
}

double srgb8_to_linear(int code) {
  const double c = code / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

}  // namespace nimbus::texture_test
