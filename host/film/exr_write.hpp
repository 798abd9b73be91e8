// EXR files written with OpenEXR itself rather than through the image I/O module: every render writes
// one, and OpenEXR's few libraries load in 2 ms where OpenImageIO's take 0.2 s.
#pragma once

#include <span>
#include <string>

#include "core/expected.hpp"
#include "core/image_io.hpp"

namespace nimbus {

// Writes `parts` (one: a single-part file; several: a multi-part file) to `file`. Each part's pixels are
// Float or UInt32, scanlines top down. Attributes become EXR attributes of the part (string, int, double),
// except "compression" (its OpenEXR name: "zip", "piz", "none", ...), which sets the part's compression
// (default zip), and "name", the part's name in a multi-part file. The error is OpenEXR's reason.
Status write_exr_file(const std::string &file, std::span<const ImagePart> parts);

}  // namespace nimbus
