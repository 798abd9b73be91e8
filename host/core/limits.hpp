// Sizes the host accepts, shared by the modules that read them.
#pragma once

#include <cstdint>

namespace nimbus {

// Pixels per side of a rendered image: the scene's `resolution`, and so the largest image `nimbus
// compare` and `nimbus lightmix` can be asked to read.
inline constexpr int64_t kMaxResolution = 16384;
// Pixels per side of an image the scene reads (environment maps, textures): twice the largest panoramas
// in common use, so that a damaged header cannot make the reader allocate without bound.
inline constexpr int64_t kMaxInputImageSide = 32768;

}  // namespace nimbus
