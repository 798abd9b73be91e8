// Test images written at test time, and a scratch directory to hold them.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "scene/scene_desc.hpp"

namespace nimbus::texture_test {

// A fresh directory for one test, removed with everything in it afterwards.
class ScratchDir {
 public:
  ScratchDir();
  ~ScratchDir();
  ScratchDir(const ScratchDir &) = delete;
  ScratchDir &operator=(const ScratchDir &) = delete;

  std::string file(const std::string &name) const { return (path_ / name).string(); }
  const std::filesystem::path &path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// Pixels row by row from the top, channels interleaved.
void write_png8(const std::string &path, int width, int height, int channels,
                const std::vector<uint8_t> &pixels);
void write_exr(const std::string &path, int width, int height, int channels,
               const std::vector<float> &pixels);
void write_text(const std::string &path, const std::string &text);

// A 2x2 RGB checker: `a` at the top-left and bottom-right texels, `b` at the other two.
void write_checker_png(const std::string &path, const uint8_t a[3], const uint8_t b[3]);

// A texture reference as the scene parser would make it (named at scene.yaml:7:22).
TextureDesc texture_at(const std::string &path);

// Whether `text` contains `part`; the failure message shows both.
::testing::AssertionResult has_substr(const std::string &text, const std::string &part);

// 8-bit sRGB code value -> linear, computed independently of the code under test (double precision).
double srgb8_to_linear(int code);

}  // namespace nimbus::texture_test
