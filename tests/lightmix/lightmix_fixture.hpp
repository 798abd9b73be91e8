// A synthetic LightMix EXR: two groups, a small residual, and other layers that must pass through.
#pragma once

#include <string>
#include <vector>

#include "core/expected.hpp"

namespace nimbus::test {

inline constexpr uint32_t kWidth = 6, kHeight = 4;

struct LightMixImage {
  // Interleaved, kWidth * kHeight pixels: RGB except depth (Y).
  std::vector<float> beauty, key, fill, albedo, depth;
};

// beauty = key + fill + a residual of about 1e-3; values from a fixed seed.
LightMixImage make_lightmix_image();

// Writes `img` as a Nimbus EXR with metadata nimbus:scene = "synthetic.yaml", nimbus:iterations = 16.
// Without `with_lightmix` the key and fill layers are left out.
Status write_lightmix_exr(const std::string &path, const LightMixImage &img, bool with_lightmix = true);

}  // namespace nimbus::test
