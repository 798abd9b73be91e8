// The built, immutable world a render reads: geometry, lights, materials, camera and pixel filter, made
// once from a SceneDesc. Nothing in it changes while a render runs (that is abi/run_state.hpp); the host
// services (abi/) hand it to plugins, and it knows nothing of plugins or the film.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "core/expected.hpp"
#include "geometry/geometry_scene.hpp"
#include "lights/light_set.hpp"
#include "materials/bsdf.hpp"
#include "materials/textured_materials.hpp"
#include "scene/scene_desc.hpp"
#include "world/camera.hpp"
#include "world/pixel_filter.hpp"
#include "world/sharp_objects.hpp"

namespace nimbus {

struct World {
  std::unique_ptr<GeometryScene> geometry;
  LightSet lights;
  std::vector<Bsdf> bsdfs;                      // one per scene material
  std::unique_ptr<TexturedMaterials> textures;  // null unless a material reads a texture
  // Per material, the index over wavelength of a dispersive dielectric (empty for the others); the whole
  // vector is empty when no material disperses, and paths then never need a wavelength.
  std::vector<std::optional<IorCurve>> dispersion;
  Camera camera;
  Shutter shutter;  // the camera's (scene time)
  PixelFilter filter;
  std::vector<SharpObject> sharp_objects;    // objects that can form caustics (sharp_objects.hpp)
  std::vector<ObjectBounds> moving_objects;  // objects that move while the shutter is open

  // Builds geometry, lights, materials and camera for `desc` (which must outlive the world), and the pixel
  // filter the render job resolved (the scene's, or the command line's instead).
  static Expected<std::unique_ptr<World>> build(const SceneDesc &desc, FilterType filter);

  bool dispersive() const { return !dispersion.empty(); }
  // The dispersive dielectric's curve of `material`, or null.
  const IorCurve *dispersion_of(uint64_t material) const {
    return material < dispersion.size() && dispersion[material] ? &*dispersion[material] : nullptr;
  }
};

}  // namespace nimbus
