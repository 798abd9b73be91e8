#include "texture_fixtures.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include "core/image_io.hpp"
#include "film/exr_write.hpp"
#include "film/png_write.hpp"

#include <cmath>
#include <fstream>

namespace nimbus::texture_test {

namespace {

// With the film's writers: these files are the texture reader's input, not its output.
void write_image(const std::string &format, const std::string &path, int width, int height, int channels,
                 PixelType type, const void *pixels) {
  static const std::vector<std::string> names = {"R", "G", "B", "A"};
  std::vector<std::string> channel_names = {"Y"};
  if (channels > 1) channel_names.assign(names.begin(), names.begin() + channels);
  ImagePart image{image_desc(uint32_t(width), uint32_t(height), channel_names, type), pixels};
  const Status written = format == "png" ? write_png_file(path, image) : write_exr_file(path, {&image, 1});
  ASSERT_TRUE(written) << written.error().message;
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
  write_image("png", path, width, height, channels, PixelType::UInt8, pixels.data());
}

void write_exr(const std::string &path, int width, int height, int channels,
               const std::vector<float> &pixels) {
  ASSERT_EQ(pixels.size(), size_t(width) * height * channels);
  write_image("openexr", path, width, height, channels, PixelType::Float, pixels.data());
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
