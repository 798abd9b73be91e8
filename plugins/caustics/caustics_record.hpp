// The solver's sample record: the camera-path layer's record (sdk/include/nimbus/cpp/sample_record.hpp)
// whose diverted element is `caustics`, the light of paths for which a merge technique is eligible
// (solver spec section 8), plus `caustics_merge`, the merged light alone. The regular lighting elements
// plus `caustics` sum to beauty.
#pragma once

#include <nimbus/cpp/sample_record.hpp>

namespace nimbus::caustics {

using sdk::ElementIds;

struct CausticsRecord : sdk::SampleRecord {
  Rgb merge;

  void reset() {
    SampleRecord::reset();
    merge = Rgb(0);
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
