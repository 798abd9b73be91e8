// A photographed-style environment map for the light tests: a ramp in azimuth with a hot spot.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include <unistd.h>

#include "core/image_io.hpp"
#include "film/exr_write.hpp"

namespace nimbus::testing {

// A 64 x 32 lat-long EXR in the temporary directory (removed by the caller): a ramp in azimuth with a
// hot spot 10^4 above the rest, as a photographed sky with the sun in it. The process id goes into the
// name, so that test runs side by side on one machine never remove each other's file.
inline std::string write_environment_map(const std::string &name) {
  const std::string path =
      (std::filesystem::temp_directory_path() / (std::to_string(::getpid()) + "-" + name)).string();
  const int w = 64, h = 32;
  std::vector<float> px(size_t(w) * h * 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c)
        px[(size_t(y) * w + x) * 3 + c] =
            0.2f + 0.5f * float(x) / w + 0.1f * float(c) + (y == 9 && x / 2 == 20 ? 2e3f : 0);
  const ImagePart image{image_desc(w, h, {"R", "G", "B"}, PixelType::Float), px.data()};
  const Status written = write_exr_file(path, {&image, 1});
  EXPECT_TRUE(written) << written.error().message;
  return path;
}

}  // namespace nimbus::testing
