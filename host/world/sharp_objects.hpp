// The objects whose material can be sharp (caustic-forming: no diffuse lobe, and a delta lobe or a GGX
// alpha that can be small), with its bounds: what the scene service's sharp_bounds reports, so
// that a photon-emitting integrator can aim at every surface that can form a caustic from the first pass
// on (caustics solver spec 6.2, projection maps).
#pragma once

#include <vector>

#include "geometry/geometry_scene.hpp"
#include "materials/bsdf.hpp"
#include "scene/scene_desc.hpp"
#include "world/object_bounds.hpp"

namespace nimbus {

struct SharpObject {
  ObjectBounds bounds;  // over the whole shutter (object_bounds.hpp)
  float min_alpha = 0;  // the smallest GGX alpha the material can have anywhere (0: delta or textured)
};

// One entry per object (shape) with positive area whose material has no diffuse lobe, in shape order.
// A material with a roughness texture counts with alpha 0: its texels may be as smooth as a mirror.
std::vector<SharpObject> find_sharp_objects(const SceneDesc &desc, const GeometryScene &geometry,
                                            const std::vector<Bsdf> &bsdfs);

}  // namespace nimbus
