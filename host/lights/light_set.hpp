// All lights of a scene, indexed as the lights service exposes them: point lights first (scene order),
// then emissive shapes (scene order). Builds LightMix groups from the `group:` keys.
#pragma once

#include <string>
#include <vector>

#include "core/expected.hpp"
#include "lights/light.hpp"
#include "scene/scene_desc.hpp"

namespace nimbus {

class LightSet {
 public:
  // Marks emissive shapes in `geo` (ShapeRecord::light_id).
  static Expected<LightSet> build(const SceneDesc &desc, GeometryScene &geo);

  uint32_t count() const { return uint32_t(lights_.size()); }
  const Light &operator[](uint32_t i) const { return lights_[i]; }
  const std::vector<std::string> &group_names() const { return group_names_; }

 private:
  std::vector<Light> lights_;
  std::vector<std::string> group_names_;
};

}  // namespace nimbus
