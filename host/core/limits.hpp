// Sizes the host accepts, shared by the modules that read them.
#pragma once

#include <cstdint>

namespace nimbus {

// Pixels per side of a rendered image: the scene's `resolution`, and so the largest image `nimbus
// compare` and `nimbus lightmix` can be asked to read.
inline constexpr int64_t kMaxResolution = 16384;

}  // namespace nimbus
