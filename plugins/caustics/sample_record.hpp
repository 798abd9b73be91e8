// Where the light of one camera sample goes: beauty always, and only the elements somebody requested.
// nimbus.pt's record (plugins/pathtracer/sample_record.hpp) extended by the caustics split: light of a
// path for which a merge technique is eligible goes to `caustics` instead of direct/indirect/emission,
// so the regular lighting elements plus `caustics` sum to beauty. Every contribution is added with the
// same float values to beauty and to its element/group, so elements sum to beauty exactly per sample.
#pragma once

#include <nimbus/nimbus.h>

#include <vector>

#include "core/math.hpp"

namespace nimbus::caustics {

// Film element ids of the optional outputs; NIMBUS_ELEMENT_INVALID when not requested.
struct ElementIds {
  nimbus_element_t direct = NIMBUS_ELEMENT_INVALID, indirect = NIMBUS_ELEMENT_INVALID,
                   emission = NIMBUS_ELEMENT_INVALID, albedo = NIMBUS_ELEMENT_INVALID,
                   normal = NIMBUS_ELEMENT_INVALID, depth = NIMBUS_ELEMENT_INVALID,
                   caustics = NIMBUS_ELEMENT_INVALID, caustics_merge = NIMBUS_ELEMENT_INVALID;
  bool split_light = false;  // any of direct / indirect / emission / caustics active
  bool lightmix = false;
};

struct SampleRecord {
  Rgb beauty, direct, indirect, emission, caustics, merge;
  Rgb albedo, normal;
  float depth = 0;
  std::vector<std::pair<uint32_t, Rgb>> groups;  // LightMix: (group, light), a few entries per sample

  void reset() {
    beauty = direct = indirect = emission = caustics = merge = albedo = normal = Rgb(0);
    depth = 0;
    groups.clear();
  }

  // Light `c` from light `group`, reaching the camera over a path of `segments` segments (1: the light
  // was seen directly; 2: it lit the first surface directly). `caustic`: some merge technique is
  // eligible for this path (solver spec section 8).
  void add(const Rgb &c, uint32_t group, uint32_t segments, const ElementIds &ids, bool caustic = false) {
    beauty += c;
    if (ids.split_light) {
      if (caustic)
        caustics += c;
      else
        (segments <= 1 ? emission : segments == 2 ? direct : indirect) += c;
    }
    add_group(c, group, ids);
  }

  // A photon-map merge contribution: always caustic light.
  void add_merge(const Rgb &c, uint32_t group, const ElementIds &ids) {
    beauty += c;
    merge += c;
    if (ids.split_light) caustics += c;
    add_group(c, group, ids);
  }

 private:
  void add_group(const Rgb &c, uint32_t group, const ElementIds &ids) {
    if (!ids.lightmix) return;
    for (auto &[g, v] : groups)
      if (g == group) {
        v += c;
        return;
      }
    groups.emplace_back(group, c);
  }
};

}  // namespace nimbus::caustics
