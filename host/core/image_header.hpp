// A check of an image file's structure before OpenImageIO opens it: OpenEXR 3.1 allocates what a header
// attribute's size field claims, and libpng what a chunk's length claims (up to 2 GiB either), before
// reading it, so a damaged size costs that much memory before the read fails.
#pragma once

#include <optional>
#include <string>

namespace nimbus {

// Why the OpenEXR or PNG file at `path` cannot be read (named .exr or .png without that format's
// signature, or an EXR header attribute or a PNG chunk claiming more bytes than the file holds), or
// nullopt. Other files, and files cut short inside a size field, are left to the reader to report.
std::optional<std::string> image_header_problem(const std::string &path);

}  // namespace nimbus
