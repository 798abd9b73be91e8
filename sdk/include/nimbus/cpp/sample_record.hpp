// Where the light of one camera sample goes: beauty always, and only the elements somebody requested
// (direct, indirect, emission, albedo, normal, depth, an integrator's diverted element) and LightMix
// groups. Every contribution is added with the same float values to beauty and to its element/group,
// so the lighting elements sum to beauty exactly. Requires C++20.
#pragma once

#include <nimbus/film.h>

#include <utility>
#include <vector>

#include <nimbus/cpp/math.hpp>

namespace nimbus::sdk {

// Film element ids of the optional outputs; NIMBUS_ELEMENT_INVALID when not requested.
struct ElementIds {
  nimbus_element_t direct = NIMBUS_ELEMENT_INVALID, indirect = NIMBUS_ELEMENT_INVALID,
                   emission = NIMBUS_ELEMENT_INVALID, albedo = NIMBUS_ELEMENT_INVALID,
                   normal = NIMBUS_ELEMENT_INVALID, depth = NIMBUS_ELEMENT_INVALID;
  // An integrator's own lighting element (the caustics solver's `caustics`): light the integrator marks
  // as diverted goes there instead of direct/indirect/emission, so the lighting elements still sum to
  // beauty.
  nimbus_element_t diverted = NIMBUS_ELEMENT_INVALID;
  bool split_light = false;  // any of direct / indirect / emission / diverted active
  bool lightmix = false;
};

struct SampleRecord {
  Rgb beauty, direct, indirect, emission, diverted;
  Rgb albedo, normal;
  float depth = 0;
  std::vector<std::pair<uint32_t, Rgb>> groups;  // LightMix: (group, light), a few entries per sample

  void reset() {
    beauty = direct = indirect = emission = diverted = albedo = normal = Rgb(0);
    depth = 0;
    groups.clear();
  }

  // Light `c` from light `group`, reaching the camera over a path of `segments` segments (1: the light
  // was seen directly; 2: it lit the first surface directly). `divert`: the integrator's own element
  // takes it instead of the split by path length. alt_ratio (PathWeight's): read by records that
  // measure a second weighting, ignored here.
  void add(const Rgb &c, uint32_t group, uint32_t segments, const ElementIds &ids, bool divert = false,
           float /*alt_ratio*/ = 1) {
    beauty += c;
    if (ids.split_light) {
      if (divert)
        diverted += c;
      else
        (segments <= 1 ? emission : segments == 2 ? direct : indirect) += c;
    }
    add_group(c, group, ids);
  }

  // Light `c` of LightMix group `group` (nothing without LightMix).
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

}  // namespace nimbus::sdk
