// All lights of a scene, indexed as the lights service exposes them: point and spot lights and the sun
// (scene order), then emissive shapes (scene order), then the environment. Builds LightMix groups from
// the `group:` keys (a light without one is its own group).
#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include "core/expected.hpp"
#include "lights/light.hpp"
#include "scene/scene_desc.hpp"

namespace nimbus {

class LightSet {
 public:
  // Marks emissive shapes in `geo` (ShapeRecord::light_id). Loads the environment map, if any.
  static Expected<LightSet> build(const SceneDesc &desc, GeometryScene &geo);

  uint32_t count() const { return uint32_t(lights_.size()); }
  const Light &operator[](uint32_t i) const { return lights_[i]; }
  const std::vector<std::string> &group_names() const { return group_names_; }
  const LightScene &scene() const { return scene_; }
  // Indices of infinite lights (sun, environment), for escaped rays.
  const std::vector<uint32_t> &infinite() const { return infinite_; }
  // Whether a light moves while the shutter is open.
  bool moves() const {
    return std::any_of(lights_.begin(), lights_.end(),
                       [](const Light &l) { return l.motion && l.motion->moves(); });
  }

 private:
  std::vector<Light> lights_;
  std::vector<std::string> group_names_;
  std::vector<uint32_t> infinite_;
  LightScene scene_;
};

// Loads a lat-long HDR/EXR image as linear RGB (errors name the path and the reason).
Expected<EnvironmentLight> load_environment_map(const std::string &path);

}  // namespace nimbus
