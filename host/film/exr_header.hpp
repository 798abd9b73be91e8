// A check of an OpenEXR file's header before OpenImageIO opens it: OpenEXR 3.1 allocates what an
// attribute's size field claims (up to 2 GiB) before reading it, so a damaged size costs that much memory
// before the read fails.
#pragma once

#include <optional>
#include <string>

namespace nimbus {

// Why the header of the OpenEXR file at `path` cannot be read (an attribute claims more bytes than the file
// holds), or nullopt. Files that are not OpenEXR, and headers cut short, are left to the reader to report.
std::optional<std::string> exr_header_problem(const std::string &path);

}  // namespace nimbus
