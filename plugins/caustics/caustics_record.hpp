// The solver's sample record: the camera-path layer's record (sdk/include/nimbus/cpp/sample_record.hpp)
// whose diverted element is `caustics`, the light of paths for which a merge technique is eligible
// (solver spec section 8), plus `caustics_merge`, the merged light alone. The regular lighting elements
// plus `caustics` sum to beauty.
#pragma once

#include <array>

#include <nimbus/cpp/sample_record.hpp>

#include "lookup_roulette.hpp"

namespace nimbus::caustics {

using sdk::ElementIds;

struct CausticsRecord : sdk::SampleRecord {
  Rgb merge;
  // Per class of lookup, the sum of q Y^2 over the sample's lookups (Y: the luminance one added), the
  // lookup roulette's measure of what the class's merges carry.
  std::array<float, kLookupClasses> lookup_moment{};
  // Luminance of the merged light from photons of even-numbered paths minus that from odd-numbered ones:
  // the two halves of a map are independent, so its square estimates the photon noise of `merge`
  // (useful_pixels.hpp).
  float merge_split = 0;
  // The sample's light as the same path would have brought it without light paths (light_path_trial.hpp):
  // each contribution times its MIS weight without them over its weight with them (the camera-path
  // layer's contributions carry that ratio as PathWeight::alt_ratio).
  Rgb without_light_paths;

  void reset() {
    SampleRecord::reset();
    merge = without_light_paths = Rgb(0);
    lookup_moment = {};
    merge_split = 0;
  }

  // The camera-path layer's contributions (hides SampleRecord::add, which the layer calls on this type).
  void add(const Rgb &c, uint32_t group, uint32_t segments, const ElementIds &ids, bool divert = false,
           float alt_ratio = 1) {
    SampleRecord::add(c, group, segments, ids, divert);
    without_light_paths += c * alt_ratio;
  }

  // A photon-map merge contribution: always caustic light. without: the same without light paths.
  void add_merge(const Rgb &c, uint32_t group, const ElementIds &ids, const Rgb &without) {
    beauty += c;
    merge += c;
    without_light_paths += without;
    if (ids.split_light) diverted += c;
    add_group(c, group, ids);
  }
};

}  // namespace nimbus::caustics
