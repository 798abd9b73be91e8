// One image file written through the image I/O module, with the library's own error text when it fails.
#pragma once

#include <span>
#include <string>

#include "core/expected.hpp"
#include "core/image_io.hpp"

namespace nimbus {

// Writes `parts` to `file` with the writer named `format` ("openexr", "png"); see ImageIo::write. Fails
// when the module cannot be loaded.
Status write_image_file(const std::string &format, const std::string &file, std::span<const ImagePart> parts);

// An image description of `width` x `height` pixels with these channels.
ImageDesc image_desc(uint32_t width, uint32_t height, std::vector<std::string> channels, PixelType type);

// A string attribute.
ImageAttribute text_attribute(std::string name, std::string text);

}  // namespace nimbus
