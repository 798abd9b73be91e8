// The image I/O module's texture cache: OpenImageIO's TextureSystem behind core/image_io.hpp's interface.
#pragma once

#include "core/image_io.hpp"

namespace nimbus {

// One for the process, created on first use and never destroyed.
const TextureCache &oiio_texture_cache();

}  // namespace nimbus
