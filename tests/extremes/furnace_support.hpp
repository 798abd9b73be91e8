// The furnace the material-extreme tests share: an object at the origin inside a sphere of radius 20
// that emits radiance 1 from both sides and absorbs everything, seen from (0, -3, 0). Everything the
// camera sees directly is exactly 1; whatever it sees through the object is the object's albedo along
// that path, which is 1 for lossless materials.
#pragma once

#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "extremes_support.hpp"

namespace nimbus::extremes {

inline constexpr uint32_t kFurnaceBlock = 8;

// `material` is the YAML of material "object"; `extra_objects` are further object list entries using it.
inline std::string furnace_scene(const std::string &material, const std::string &extra_objects = "",
                                 int resolution = 24, int max_depth = 128) {
  return R"(
render: { resolution: [)" +
         std::to_string(resolution) + ", " + std::to_string(resolution) +
         "], seed: 1, max_depth: " + std::to_string(max_depth) + R"( }
camera: { position: [0, -3, 0], look_at: [0, 0, 0], up: [0, 0, 1], fov: 40 }
materials:
  object: )" +
         material + R"(
  lamp: { type: diffuse, albedo: [0, 0, 0] }
objects:
  - { shape: sphere, center: [0, 0, 0], radius: 1, material: object }
  - { shape: sphere, center: [0, 0, 0], radius: 20, material: lamp, two_sided: true,
      emission: { radiance: [1, 1, 1] } }
)" + extra_objects;
}

// Calls f(block_x, block_y, mask) for every kFurnaceBlock-square block of the image.
template <class F>
void for_each_block(const Rendered &img, F &&f) {
  for (uint32_t by = 0; by + kFurnaceBlock <= img.height; by += kFurnaceBlock)
    for (uint32_t bx = 0; bx + kFurnaceBlock <= img.width; bx += kFurnaceBlock)
      f(bx, by, [bx, by](uint32_t x, uint32_t y) {
        return x >= bx && x < bx + kFurnaceBlock && y >= by && y < by + kFurnaceBlock;
      });
}

// Every channel's image mean is `level` within `rel` (and within 5 standard errors), and so is every
// block's mean within its own noise plus `rel`: a local gain or loss cannot hide in the average.
inline void expect_furnace_level(const Rendered &img, double level, double rel) {
  for (int c = 0; c < 3; ++c) {
    const Estimate m = channel_mean(img, c);
    if (verbose()) std::printf("  furnace ch%d: mean %.6f std error %.2g\n", c, m.mean, m.std_error);
    EXPECT_NEAR(m.mean, level, std::min(rel * level, std::max(5 * m.std_error, 1e-4)))
        << "channel " << c << ", std error " << m.std_error;
    for_each_block(img, [&](uint32_t bx, uint32_t by, const PixelMask &mask) {
      const Estimate b = channel_mean(img, c, mask);
      EXPECT_NEAR(b.mean, level, 5 * b.std_error + rel * level)
          << "channel " << c << ", block (" << bx << ", " << by << "), std error " << b.std_error;
    });
  }
}

// Lossy materials: no channel gains energy anywhere (image and block means at most 1 plus noise), and the
// image mean is at least `floor`.
inline void expect_furnace_bounded(const Rendered &img, double floor) {
  for (int c = 0; c < 3; ++c) {
    const Estimate m = channel_mean(img, c);
    if (verbose()) std::printf("  furnace ch%d: mean %.6f std error %.2g\n", c, m.mean, m.std_error);
    EXPECT_LE(m.mean, 1 + 5 * m.std_error + 1e-4) << "channel " << c << ", std error " << m.std_error;
    EXPECT_GE(m.mean, floor) << "channel " << c;
    for_each_block(img, [&](uint32_t bx, uint32_t by, const PixelMask &mask) {
      const Estimate b = channel_mean(img, c, mask);
      EXPECT_LE(b.mean, 1 + 5 * b.std_error + 1e-3)
          << "channel " << c << ", block (" << bx << ", " << by << "), std error " << b.std_error;
    });
  }
}

}  // namespace nimbus::extremes
