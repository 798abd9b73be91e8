// PNG files written with libpng itself rather than through the image I/O module: every render writes a
// preview, and libpng loads at once where OpenImageIO's libraries take 0.2 s.
#pragma once

#include <string>

#include "core/expected.hpp"
#include "core/image_io.hpp"

namespace nimbus {

// Writes an 8-bit image of 1 (grey), 2 (grey, alpha), 3 (RGB) or 4 (RGBA) channels, its pixels interleaved,
// scanlines top down, as stored (no alpha association). String attributes become tEXt chunks (PNG's
// keywords: "Software", "Description", ...); others are ignored. The error is libpng's or the system's
// reason.
Status write_png_file(const std::string &file, const ImagePart &image);

}  // namespace nimbus
