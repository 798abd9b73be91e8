// One OpenImageIO write, with OIIO's own error text when it fails.
#pragma once

#include <OpenImageIO/imageio.h>

#include <string>

#include "core/expected.hpp"

namespace nimbus {

// Writes `pixels` (laid out as `spec` says: spec.format, channel-interleaved, scanlines top down) to
// `file` with the OIIO plugin named `format` ("openexr", "png"). The format is explicit because the
// temporary files this is used for have no image extension.
Status write_oiio_image(const std::string &format, const std::string &file, const OIIO::ImageSpec &spec,
                        const void *pixels);

}  // namespace nimbus
