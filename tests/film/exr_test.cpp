// The multi-layer EXR: channel names, bit-exact values, metadata, and atomic replacement.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include "film/exr_write.hpp"
#include "film/film.hpp"
#include "film/image_read.hpp"
#include "scratch_dir.hpp"

namespace nimbus {
namespace exr_test {

using test::read_bytes;
using test::ScratchDir;

// 7x5 (odd, so row/column mix-ups show), beauty + albedo + depth + a LightMix layer, with values far
// above half's 65504 and far below its precision, over 3 iterations.
struct Fixture {
  Film film{7, 5};
  int32_t albedo, depth, key, normal;

  Fixture() {
    albedo = film.register_element("albedo", 3, Film::kAverage);
    depth = film.register_element("depth", 1, Film::kAverage);
    key = film.register_element("lightmix.key", 3, Film::kSplat);
    normal = film.register_element("normal", 3, Film::kAverage);  // registered, never requested
    for (const char *name : {"albedo", "depth", "lightmix.key"}) film.request(name);
    EXPECT_TRUE(film.allocate().ok());
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int i = 0; i < 3; ++i) {
      for (uint32_t y = 0; y < 5; ++y) {
        for (uint32_t x = 0; x < 7; ++x) {
          const float beauty[3] = {u(rng) * 1e6f, u(rng) * 1e-7f, u(rng)};
          const float a[3] = {u(rng), u(rng), u(rng)};
          const float d = u(rng) * 100.0f;
          const float k[3] = {u(rng) * 3, u(rng) * 3, u(rng) * 3};
          film.accumulate(Film::kBeauty, x, y, beauty);
          film.accumulate(albedo, x, y, a);
          film.accumulate(depth, x, y, &d);
          film.accumulate(key, x, y, k);
        }
      }
      film.end_iteration();
    }
  }

  Status write(const std::string &path) const {
    return film.write_exr(path, {{"scene", "scenes/default.yaml"}, {"integrator", "nimbus.pt"}},
                          {{"iterations", double(film.iterations())},
                           {"seconds", 12.345678901234},
                           {"seed", -7},
                           {"paths_traced", 6e9}});
  }
};

std::vector<float> plane(const std::vector<float> &image, size_t channels, size_t c) {
  std::vector<float> out;
  for (size_t i = c; i < image.size(); i += channels) out.push_back(image[i]);
  return out;
}

TEST(FilmExr, RoundTripIsBitExactWithLayerNamesAndMetadata) {
  ScratchDir dir;
  Fixture f;
  const std::string path = dir.file("out.exr");
  const Status status = f.write(path);
  ASSERT_TRUE(status.ok()) << status.error().message;

  const Expected<ImageLayers> read = read_exr_layers(path);
  ASSERT_TRUE(read.ok()) << read.error().message;
  const ImageLayers &img = read.value();
  EXPECT_EQ(img.width, 7u);
  EXPECT_EQ(img.height, 5u);
  std::vector<std::string> names;
  for (const auto &[name, data] : img.channels) names.push_back(name);
  EXPECT_EQ(names, (std::vector<std::string>{"B", "G", "R", "albedo.B", "albedo.G", "albedo.R", "depth.Y",
                                             "lightmix.key.B", "lightmix.key.G", "lightmix.key.R"}));

  const auto expect_layer = [&](const std::string &layer, const std::vector<std::string> &channels,
                                int32_t id) {
    SCOPED_TRACE(layer);
    const std::vector<float> expected = f.film.resolve(id);
    for (size_t c = 0; c < channels.size(); ++c) {
      ASSERT_TRUE(img.channels.count(channels[c]));
      EXPECT_EQ(img.channels.at(channels[c]), plane(expected, channels.size(), c)) << channels[c];
    }
    ASSERT_TRUE(img.layers.count(layer));
    EXPECT_EQ(img.layers.at(layer).channel_names, channels);
    EXPECT_EQ(img.layers.at(layer).data, expected);
  };
  expect_layer("beauty", {"R", "G", "B"}, Film::kBeauty);
  expect_layer("albedo", {"albedo.R", "albedo.G", "albedo.B"}, f.albedo);
  expect_layer("depth", {"depth.Y"}, f.depth);
  expect_layer("lightmix.key", {"lightmix.key.R", "lightmix.key.G", "lightmix.key.B"}, f.key);
  EXPECT_EQ(img.layers.size(), 4u);
  EXPECT_GT(*std::max_element(img.channels.at("R").begin(), img.channels.at("R").end()), 65504.0f);

  EXPECT_EQ(img.strings.at("nimbus:scene"), "scenes/default.yaml");
  EXPECT_EQ(img.strings.at("nimbus:integrator"), "nimbus.pt");
  EXPECT_EQ(img.strings.at("Software").rfind("Nimbus ", 0), 0u);
  EXPECT_EQ(img.strings.at("compression"), "zip");
  EXPECT_EQ(img.numbers.at("nimbus:iterations"), 3.0);
  EXPECT_EQ(img.numbers.at("nimbus:seconds"), 12.345678901234);
  EXPECT_EQ(img.numbers.at("nimbus:seed"), -7.0);
  EXPECT_EQ(img.numbers.at("nimbus:paths_traced"), 6e9);
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"out.exr"});
}

TEST(FilmExr, BeautyOnlyFilmWritesJustRGB) {
  ScratchDir dir;
  Film film(3, 2);
  film.register_element("albedo", 3, Film::kAverage);
  ASSERT_TRUE(film.allocate().ok());
  ASSERT_TRUE(film.write_exr(dir.file("b.exr"), {}, {}).ok());
  const Expected<ImageLayers> read = read_exr_layers(dir.file("b.exr"));
  ASSERT_TRUE(read.ok()) << read.error().message;
  EXPECT_EQ(read->channels.size(), 3u);
  EXPECT_EQ(read->layers.size(), 1u);
}

TEST(FilmExr, MissingDirectoryIsAnErrorNamingThePathAndLeavesNothing) {
  ScratchDir dir;
  Fixture f;
  const std::string path = dir.file("missing/out.exr");
  const Status status = f.write(path);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.error().message.find(path), std::string::npos) << status.error().message;
  EXPECT_NE(status.error().message.find("does not exist"), std::string::npos) << status.error().message;
  EXPECT_TRUE(dir.entries().empty());
}

TEST(FilmExr, FailedWriteLeavesTheExistingFileUntouched) {
  ScratchDir dir;
  Fixture f;
  const std::string path = dir.file("out.exr");
  ASSERT_TRUE(f.write(path).ok());
  const std::string before = read_bytes(path);
  ASSERT_FALSE(before.empty());

  // Occupy the temporary name with a directory so the writer itself fails (root ignores permissions,
  // so a read-only directory would not do).
  const std::string blocker = path + ".tmp-" + std::to_string(::getpid());
  std::filesystem::create_directory(blocker);
  std::ofstream(blocker + "/keep") << "x";
  Film other(7, 5);
  const Status status = other.write_exr(path, {}, {});
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.error().message.find(path), std::string::npos) << status.error().message;
  EXPECT_EQ(read_bytes(path), before);
  EXPECT_TRUE(std::filesystem::exists(blocker + "/keep")) << "the writer deleted something it did not make";
  std::filesystem::remove_all(blocker);

  // And the same write succeeds once the name is free, replacing the old image.
  ASSERT_TRUE(other.write_exr(path, {}, {}).ok());
  EXPECT_NE(read_bytes(path), before);
  const Expected<ImageLayers> read = read_exr_layers(path);
  ASSERT_TRUE(read.ok());
  EXPECT_EQ(read->channels.size(), 3u);
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"out.exr"});
}

TEST(FilmExr, RenameOntoADirectoryFailsAndCleansUp) {
  ScratchDir dir;
  Film film(2, 2);
  const std::string path = dir.file("taken");
  std::filesystem::create_directories(path + "/inside");
  const Status status = film.write_exr(path, {}, {});
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.error().message.find(path), std::string::npos) << status.error().message;
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"taken"});
}

// OpenEXR's writer on a full disk, and on what EXR cannot hold: errors with the reason, no exception.
TEST(ExrWrite, FullDiskAndEightBitChannelsAreErrors) {
  std::vector<float> noise(256 * 256 * 3);
  std::mt19937 rng(3);
  for (float &v : noise) v = std::uniform_real_distribution<float>(0, 1)(rng);  // incompressible
  const ImagePart part{image_desc(256, 256, {"R", "G", "B"}, PixelType::Float), noise.data()};
  const Status full = write_exr_file("/dev/full", {&part, 1});
  ASSERT_FALSE(full.ok());
  EXPECT_NE(full.error().message.find("No space left on device"), std::string::npos) << full.error().message;
  EXPECT_EQ(full.error().message.find('\n'), std::string::npos) << full.error().message;

  const uint8_t byte = 0;
  const ImagePart bytes{image_desc(1, 1, {"Y"}, PixelType::UInt8), &byte};
  ScratchDir dir;
  const Status refused = write_exr_file(dir.file("x.exr"), {&bytes, 1});
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error().message, "EXR has no 8-bit channels");
}

TEST(FilmExr, ReadingAMissingFileIsAnError) {
  const Expected<ImageLayers> read = read_exr_layers("/nonexistent/nimbus.exr");
  ASSERT_FALSE(read.ok());
  EXPECT_NE(read.error().message.find("/nonexistent/nimbus.exr"), std::string::npos);
}

}  // namespace exr_test
}  // namespace nimbus
