// Scene-linear film values to display-encoded values through an OpenColorIO config.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/expected.hpp"

namespace nimbus {

// Transforms `rgb` (width * height interleaved RGB) in place from the config's scene_linear role to its
// default display and that display's default view. Errors name the config path and OCIO's reason.
Status apply_display_transform(const std::string &config_path, std::vector<float> &rgb, uint32_t width,
                               uint32_t height);

}  // namespace nimbus
