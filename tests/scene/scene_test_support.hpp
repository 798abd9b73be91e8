// Shared helpers for the scene parser tests.
#pragma once

#include <gtest/gtest.h>

#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <string>

#include "scene/scene_parser.hpp"

namespace nimbus::test {

inline const std::string kFixtures = std::string(NIMBUS_SOURCE_DIR) + "/tests/scene/fixtures";

// Vectors and colours (Rgb is a Vec3f) compared component by component.
inline void expect_vec(const Vec3f &actual, const Vec3f &expected, float tolerance = 1e-5f) {
  EXPECT_NEAR(actual.x, expected.x, tolerance);
  EXPECT_NEAR(actual.y, expected.y, tolerance);
  EXPECT_NEAR(actual.z, expected.z, tolerance);
}

// Parses inline YAML that must be valid; fails the test with the parser's message otherwise.
inline SceneDesc parse_ok(const std::string &yaml) {
  Expected<SceneDesc> scene = parse_scene_string(yaml, "test.yaml");
  EXPECT_TRUE(scene.ok()) << scene.error().message;
  return scene.ok() ? std::move(scene).value() : SceneDesc{};
}

// Checks that an error message is exactly one line, starts with "FILE:LINE:COLUMN: error: WHAT: " and
// contains `contains`.
inline ::testing::AssertionResult error_is(const Expected<SceneDesc> &result, const std::string &file,
                                           int line, int column, const std::string &what,
                                           const std::string &contains) {
  if (result.ok()) return ::testing::AssertionFailure() << "parsed without error";
  const std::string &message = result.error().message;
  const std::string prefix =
      file + ":" + std::to_string(line) + ":" + std::to_string(column) + ": error: " + what + ": ";
  if (message.rfind(prefix, 0) != 0)
    return ::testing::AssertionFailure()
           << "expected prefix \"" << prefix << "\"\n  got \"" << message << "\"";
  if (message.find(contains) == std::string::npos)
    return ::testing::AssertionFailure() << "expected \"" << contains << "\" in \"" << message << "\"";
  if (message.find('\n') != std::string::npos)
    return ::testing::AssertionFailure() << "message spans several lines: \"" << message << "\"";
  return ::testing::AssertionSuccess() << message;
}

// Parses inline YAML as "test.yaml" and checks the error as above.
inline ::testing::AssertionResult fails_at(const std::string &yaml, int line, int column,
                                           const std::string &what, const std::string &contains = "") {
  return error_is(parse_scene_string(yaml, "test.yaml"), "test.yaml", line, column, what, contains);
}

// A fresh directory for files a test writes (included scenes, glTF files, environment maps), removed with
// everything in it when the test ends. Unique per process and instance, so parallel ctest runs are apart.
class TempDir {
 public:
  TempDir() {
    static std::atomic<int> counter{0};
    path_ = std::filesystem::temp_directory_path() /
            ("nimbus-scene-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir &) = delete;
  TempDir &operator=(const TempDir &) = delete;

  const std::filesystem::path &path() const { return path_; }
  // Writes `text` to `relative` (creating directories) and returns the full path as a string.
  std::string write(const std::string &relative, const std::string &text) const {
    const std::filesystem::path p = path_ / relative;
    std::filesystem::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << text;
    return p.string();
  }

 private:
  std::filesystem::path path_;
};

}  // namespace nimbus::test
