// Where the light of one camera sample goes: beauty always, and only the elements somebody requested
// (direct, indirect, emission, albedo, normal, depth) and LightMix groups. Every contribution is added
// with the same float values to beauty and to its element/group, so elements sum to beauty exactly.
#pragma once

#include <nimbus/nimbus.h>

#include <vector>

#include "core/math.hpp"

namespace nimbus::pt {

// Film element ids of the optional outputs; NIMBUS_ELEMENT_INVALID when not requested.
struct ElementIds {
  nimbus_element_t direct = NIMBUS_ELEMENT_INVALID, indirect = NIMBUS_ELEMENT_INVALID,
                   emission = NIMBUS_ELEMENT_INVALID, albedo = NIMBUS_ELEMENT_INVALID,
                   normal = NIMBUS_ELEMENT_INVALID, depth = NIMBUS_ELEMENT_INVALID;
  bool split_light = false;  // any of direct / indirect / emission active
  bool lightmix = false;
};

struct SampleRecord {
  Rgb beauty, direct, indirect, emission;
  Rgb albedo, normal;
  float depth = 0;
  std::vector<std::pair<uint32_t, Rgb>> groups;  // LightMix: (group, light), a few entries per sample

  void reset() {
    beauty = direct = indirect = emission = albedo = normal = Rgb(0);
    depth = 0;
    groups.clear();
  }

  // Light `c` from light `group`, reaching the camera over a path of `segments` segments (1: the light
  // was seen directly; 2: it lit the first surface directly).
  void add(const Rgb &c, uint32_t group, uint32_t segments, const ElementIds &ids) {
    beauty += c;
    if (ids.split_light) (segments <= 1 ? emission : segments == 2 ? direct : indirect) += c;
    if (!ids.lightmix) return;
    for (auto &[g, v] : groups)
      if (g == group) {
        v += c;
        return;
      }
    groups.emplace_back(group, c);
  }
};

}  // namespace nimbus::pt
