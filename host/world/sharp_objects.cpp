#include "world/sharp_objects.hpp"

namespace nimbus {

std::vector<SharpObject> find_sharp_objects(const SceneDesc &desc, const GeometryScene &geometry,
                                            const std::vector<Bsdf> &bsdfs) {
  std::vector<SharpObject> out;
  for (const ShapeRecord &s : geometry.shapes()) {
    if (!(s.area > 0) || s.material >= bsdfs.size()) continue;
    const Bsdf &b = bsdfs[s.material];
    if (b.lobes() & NIMBUS_LOBE_DIFFUSE) continue;
    const bool textured = !desc.materials[s.material].roughness_texture.empty();
    const ObjectBounds bounds = object_bounds(s);
    if (bounds.sphere.empty()) continue;
    out.push_back({bounds, textured ? 0.0f : b.min_alpha()});
  }
  return out;
}

}  // namespace nimbus
