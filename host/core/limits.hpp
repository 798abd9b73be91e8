// Sizes the host accepts, shared by the modules that read them.
#pragma once

#include <cstdint>
#include <string>

namespace nimbus {

// Pixels per side of a rendered image: the scene's `resolution`, and so the largest image `nimbus
// compare` and `nimbus lightmix` can be asked to read.
inline constexpr int64_t kMaxResolution = 16384;
// Pixels per side of an image the scene reads (environment maps, textures): twice the largest panoramas
// in common use, so that a damaged header cannot make the reader allocate without bound.
inline constexpr int64_t kMaxInputImageSide = 32768;

// Why an input image of width x height cannot be read ("100000x100000 pixels, more than 32768 per side"),
// or empty when it can.
inline std::string oversized_input_image(int64_t width, int64_t height) {
  if (width <= kMaxInputImageSide && height <= kMaxInputImageSide) return {};
  return std::to_string(width) + "x" + std::to_string(height) + " pixels, more than " +
         std::to_string(kMaxInputImageSide) + " per side";
}

}  // namespace nimbus
