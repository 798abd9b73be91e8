// LightMix recombination: relighting a finished render from its per-group layers, without rendering again.
//
// A LightMix render holds one RGB layer "lightmix.<group>" per light group; together they sum to beauty.
// Recombining scales each group by a number and an RGB tint:
//
//   beauty' = Σ_g scale_g · color_g · layer_g  +  (beauty − Σ_g layer_g)
//
// The residual (beauty − Σ layers) keeps whatever no group accounts for, normally ~0 (e.g. samples a
// plugin could not attribute), so scale 1 everywhere gives beauty back up to float rounding.
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "core/expected.hpp"
#include "film/image_read.hpp"

namespace nimbus {

struct LightMixSetting {
  std::string group;  // "key" for the layer "lightmix.key"
  float scale = 1;
  std::array<float, 3> color{1, 1, 1};
};

// Parses "GROUP=SCALE" or "GROUP=SCALE,R,G,B" (also "lightmix.GROUP=..."); scale and colour must be finite
// and non-negative. The error quotes the text and says what is wrong.
Expected<LightMixSetting> parse_lightmix_setting(std::string_view text);

// The groups of the image's LightMix layers ("key", not "lightmix.key"), sorted.
std::vector<std::string> lightmix_groups(const ImageLayers &image);

// Recombines `image` in place: beauty as above, and every LightMix layer replaced by its scaled self, so
// that in the result the layers plus the same residual still sum to beauty, and mixing the result again
// composes with this mix. Groups not named keep scale 1; every other layer is untouched. Both
// `image.layers` and `image.channels` are updated. Returns a description of the full mix for the output's
// metadata, every group in order, e.g. "fill=1;key=2,1,0.5,0.5". Errors (image unchanged): no beauty, no
// LightMix layers, a LightMix layer that is not RGB, an unknown group (the message lists the available
// ones), a group set twice.
Expected<std::string> recombine_lightmix(ImageLayers &image, const std::vector<LightMixSetting> &settings);

}  // namespace nimbus
