// The PNG preview: OCIO display transform, 8-bit quantisation, config lookup and config errors.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>

#include "film/film.hpp"
#include "film/png_write.hpp"
#include "scratch_dir.hpp"

namespace nimbus {
namespace png_test {

using test::ScratchDir;

const std::string kSourceConfig = NIMBUS_SOURCE_DIR "/host/film/ocio/config.ocio";

std::unique_ptr<Film> grey_ramp(const std::vector<float> &values) {
  auto film = std::make_unique<Film>(static_cast<uint32_t>(values.size()), 1);
  for (uint32_t x = 0; x < values.size(); ++x) {
    const float v[3] = {values[x], values[x], values[x]};
    film->accumulate(Film::kBeauty, x, 0, v);
  }
  film->end_iteration();
  return film;
}

// The bytes as stored: OpenImageIO would otherwise multiply colour by alpha as it reads.
std::vector<uint8_t> read_png(const std::string &path, OIIO::ImageSpec &spec) {
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto in = OIIO::ImageInput::open(path, &config);
  EXPECT_TRUE(in) << OIIO::geterror();
  if (!in) return {};
  spec = in->spec();
  std::vector<uint8_t> pixels(size_t(spec.width) * spec.height * spec.nchannels);
  EXPECT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, pixels.data()))
      << in->geterror();
  return pixels;
}

double srgb_encode(double v) { return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1 / 2.4) - 0.055; }

TEST(FilmPng, DisplayTransformEncodesSrgb) {
  ScratchDir dir;
  const auto film = grey_ramp({0.18f, 1.0f, 0.0f, 4.0f, 0.001f, 0.05f});
  const std::string path = dir.file("preview.png");
  const Status status = film->write_png(path, kSourceConfig);
  ASSERT_TRUE(status.ok()) << status.error().message;
  OIIO::ImageSpec spec;
  const std::vector<uint8_t> px = read_png(path, spec);
  EXPECT_EQ(spec.nchannels, 3);
  EXPECT_EQ(spec.format, OIIO::TypeDesc::UINT8);
  EXPECT_EQ(spec.get_string_attribute("Software"), "Nimbus " NIMBUS_VERSION_STRING);
  ASSERT_EQ(px.size(), 6u * 3u);
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(px[0 * 3 + c], 118) << "0.18 linear is sRGB 117.65";
    EXPECT_EQ(px[1 * 3 + c], 255);
    EXPECT_EQ(px[2 * 3 + c], 0);
    EXPECT_EQ(px[3 * 3 + c], 255) << "over-range clips";
    EXPECT_EQ(px[4 * 3 + c], 3) << "linear toe: 12.92 * 0.001 * 255 = 3.29";
    EXPECT_EQ(px[5 * 3 + c], 63) << "0.05 linear is sRGB 63.19";
  }
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"preview.png"});
}

TEST(FilmPng, RampMatchesThePiecewiseSrgbCurve) {
  ScratchDir dir;
  std::vector<float> values;
  for (int i = 0; i <= 64; ++i) values.push_back(std::pow(float(i) / 64.0f, 2.2f));
  const auto film = grey_ramp(values);
  ASSERT_TRUE(film->write_png(dir.file("ramp.png"), kSourceConfig).ok());
  OIIO::ImageSpec spec;
  const std::vector<uint8_t> px = read_png(dir.file("ramp.png"), spec);
  ASSERT_EQ(px.size(), values.size() * 3);
  for (size_t i = 0; i < values.size(); ++i) {
    // OCIO's CPU path may use a fast pow; allow one code value at rounding boundaries.
    EXPECT_NEAR(px[i * 3], 255.0 * srgb_encode(values[i]), 0.5 + 1e-3) << "value " << values[i];
  }
}

TEST(FilmPng, MissingConfigIsAClearErrorAndWritesNothing) {
  ScratchDir dir;
  const auto film = grey_ramp({0.5f});
  const std::string config = dir.file("no/config.ocio");
  const Status status = film->write_png(dir.file("p.png"), config);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.error().message.find(config), std::string::npos) << status.error().message;
  EXPECT_NE(status.error().message.find("no such file"), std::string::npos) << status.error().message;
  EXPECT_TRUE(dir.entries().empty());
}

TEST(FilmPng, InvalidConfigNamesThePathAndOcioReason) {
  ScratchDir dir;
  const std::string config = dir.file("bad.ocio");
  std::ofstream(config) << "ocio_profile_version: 2\ncolorspaces:\n  - !<ColorSpace> {name: a}\n"
                           "displays: {d: [!<View> {name: v, colorspace: nope}]}\n";
  const auto film = grey_ramp({0.5f});
  const Status status = film->write_png(dir.file("p.png"), config);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.error().message.find("OCIO config '" + config + "': "), std::string::npos)
      << status.error().message;
  EXPECT_GT(status.error().message.size(), ("OCIO config '" + config + "': ").size() + 5);
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"bad.ocio"});
}

TEST(FilmPng, PngIntoMissingDirectoryIsAnError) {
  ScratchDir dir;
  const auto film = grey_ramp({0.5f});
  const std::string path = dir.file("missing/p.png");
  const Status status = film->write_png(path, kSourceConfig);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.error().message.find(path), std::string::npos) << status.error().message;
}

// Restores NIMBUS_OCIO_CONFIG whatever the test does with it.
class OcioEnv : public ::testing::Test {
 protected:
  void SetUp() override {
    if (const char *v = std::getenv("NIMBUS_OCIO_CONFIG")) saved_ = v;
    had_ = std::getenv("NIMBUS_OCIO_CONFIG") != nullptr;
  }
  void TearDown() override {
    if (had_)
      setenv("NIMBUS_OCIO_CONFIG", saved_.c_str(), 1);
    else
      unsetenv("NIMBUS_OCIO_CONFIG");
  }
  std::string saved_;
  bool had_ = false;
};

TEST_F(OcioEnv, EnvironmentVariableWinsEvenIfTheFileIsMissing) {
  setenv("NIMBUS_OCIO_CONFIG", "/somewhere/else.ocio", 1);
  EXPECT_EQ(default_ocio_config_path(), "/somewhere/else.ocio");
}

TEST_F(OcioEnv, BuildTreeCopyIsFoundNextToTheExecutable) {
  unsetenv("NIMBUS_OCIO_CONFIG");
  const std::string found = default_ocio_config_path();
  const std::filesystem::path build_copy = NIMBUS_BINARY_DIR "/" NIMBUS_INSTALL_DATA_DIR "/ocio/config.ocio";
  ASSERT_TRUE(std::filesystem::exists(found)) << found;
  EXPECT_TRUE(std::filesystem::equivalent(found, build_copy)) << found;
  // And it is a working config.
  ScratchDir dir;
  const Status status = grey_ramp({0.18f})->write_png(dir.file("d.png"), found);
  EXPECT_TRUE(status.ok()) << status.error().message;
}

// libpng's writer, read back by OpenImageIO: every channel count, bytes as given (alpha not applied),
// text attributes as tEXt chunks; a file that cannot be created is an error with the system's reason.
TEST(PngWrite, EveryChannelCountRoundTripsThroughAnIndependentReader) {
  ScratchDir dir;
  for (int channels = 1; channels <= 4; ++channels) {
    std::vector<uint8_t> bytes;
    for (int i = 0; i < 3 * 2 * channels; ++i) bytes.push_back(uint8_t(i * 37 % 256));  // alpha 0 included
    const std::vector<std::string> names = {"R", "G", "B", "A"};
    ImageDesc desc = image_desc(3, 2, {names.begin(), names.begin() + channels}, PixelType::UInt8);
    desc.attributes.push_back(text_attribute("Description", "channels " + std::to_string(channels)));
    const std::string path = dir.file("c" + std::to_string(channels) + ".png");
    const Status written = write_png_file(path, {desc, bytes.data()});
    ASSERT_TRUE(written.ok()) << written.error().message;
    OIIO::ImageSpec spec;
    EXPECT_EQ(read_png(path, spec), bytes) << channels << " channels";
    EXPECT_EQ(spec.nchannels, channels);
    EXPECT_EQ(spec.get_string_attribute("ImageDescription"), "channels " + std::to_string(channels));
  }
  const Status missing =
      write_png_file(dir.file("no-such-dir/x.png"), {image_desc(1, 1, {"Y"}, PixelType::UInt8), "\x7f"});
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.error().message, "No such file or directory");
  // A full disk, whether libpng's fwrite (a large image) or the final flush (a small one) finds it.
  for (const uint32_t side : {1u, 512u}) {
    std::vector<uint8_t> grey(size_t(side) * side);
    uint32_t state = 1;
    for (uint8_t &g : grey) g = uint8_t((state = state * 1664525u + 1013904223u) >> 24);  // incompressible
    const Status full =
        write_png_file("/dev/full", {image_desc(side, side, {"Y"}, PixelType::UInt8), grey.data()});
    ASSERT_FALSE(full.ok()) << side;
    EXPECT_NE(full.error().message.find("No space left on device"), std::string::npos)
        << full.error().message;
  }
}

}  // namespace png_test
}  // namespace nimbus
