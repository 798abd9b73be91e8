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

  void reset() {
    SampleRecord::reset();
    merge = Rgb(0);
    lookup_moment = {};
    merge_split = 0;
  }

  // A photon-map merge contribution: always caustic light.
  void add_merge(const Rgb &c, uint32_t group, const ElementIds &ids) {
    beauty += c;
    merge += c;
    if (ids.split_light) diverted += c;
    add_group(c, group, ids);
  }
};

}  // namespace nimbus::caustics
