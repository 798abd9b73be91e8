// A damaged environment map is an error naming the file and the reason, never a crash or a black sky:
// a file that is not an image, an EXR cut off in its pixel data, a missing file, and headers claiming
// sizes the file does not hold.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "lights/environment_map_fixture.hpp"
#include "lights/light_set.hpp"

namespace nimbus {
namespace environment_map_errors_test {

// The error load_environment_map gives for `path` (the test fails if it loads).
std::string load_error(const std::string &path) {
  auto env = load_environment_map(path);
  EXPECT_FALSE(env.ok()) << path << " loaded";
  return env.ok() ? std::string() : env.error().message;
}

void expect_names_path_and_reason(const std::string &message, const std::string &path) {
  EXPECT_EQ(message.rfind(path + ": cannot read environment map: ", 0), 0u) << message;
  EXPECT_GT(message.size(), path.size() + 35) << "a reason after the path: " << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << "one line: " << message;
}

TEST(EnvironmentMapErrors, NotAnImage) {
  const std::string path = (std::filesystem::temp_directory_path() / "nimbus_env_garbage.exr").string();
  std::ofstream(path) << "this is not an OpenEXR file\n";
  expect_names_path_and_reason(load_error(path), path);
  std::filesystem::remove(path);
}

TEST(EnvironmentMapErrors, TruncatedPixelData) {
  const std::string path = testing::write_environment_map("nimbus_env_truncated.exr");
  std::filesystem::resize_file(path, std::filesystem::file_size(path) / 2);
  expect_names_path_and_reason(load_error(path), path);
  std::filesystem::remove(path);
}

TEST(EnvironmentMapErrors, MissingFile) {
  const std::string path = (std::filesystem::temp_directory_path() / "nimbus_env_missing.exr").string();
  std::filesystem::remove(path);
  expect_names_path_and_reason(load_error(path), path);
}

// Headers that claim more than the file holds or a 100000-pixel side: refused before the image library
// allocates what they claim (tests/fuzz/image/regressions).
TEST(EnvironmentMapErrors, HeadersClaimingHugeSizesAreRefusedBeforeAllocating) {
  const std::string dir = std::string(NIMBUS_SOURCE_DIR) + "/tests/fuzz/image/regressions/";
  for (const char *name : {"attribute_size_2gib.exr", "png_chunk_length_1.7gib.png", "huge_header.png"}) {
    const std::string message = load_error(dir + name);
    expect_names_path_and_reason(message, dir + name);
    std::printf("%s: %s\n", name, message.c_str());
  }
}

// 55 bytes named .exr that OpenImageIO's WebP reader, tried when OpenEXR's refuses them, takes for a
// 7711x14457 lossless image and decodes (~600 MB, seconds) before failing: refused by their name's format.
TEST(EnvironmentMapErrors, FileNamedExrMustBeOpenExr) {
  const std::string path =
      std::string(NIMBUS_SOURCE_DIR) + "/tests/fuzz/image/regressions/webp_bitstream_named_exr.exr";
  const std::string message = load_error(path);
  expect_names_path_and_reason(message, path);
  EXPECT_NE(message.find("not an OpenEXR file"), std::string::npos) << message;
}

}  // namespace environment_map_errors_test
}  // namespace nimbus
