#include "world/sharp_objects.hpp"

#include <algorithm>

namespace nimbus {
namespace {

// The shape's box and the smaller of the sphere around it and Ritter's sphere around its vertices.
SharpObject shape_bounds(const ShapeRecord &s) {
  SharpObject o;
  if (s.type == ShapeType::Sphere || s.type == ShapeType::Disk) {
    // A disk's box is its sphere's: a bound, and disks are rarely sharp.
    o.lo = s.center - Vec3f(s.radius), o.hi = s.center + Vec3f(s.radius);
    o.sphere = {s.center, s.radius};
    return o;
  }
  if (!s.mesh || s.mesh->positions.empty()) return o;
  o.lo = Vec3f(kInfinity), o.hi = Vec3f(-kInfinity);
  for (const Vec3f &p : s.mesh->positions) o.lo = min(o.lo, p), o.hi = max(o.hi, p);
  o.sphere = {(o.lo + o.hi) * 0.5f, 0.5f * length(o.hi - o.lo)};
  if (const Sphere tight = ritter_bounding_sphere(s.mesh->positions); tight.radius < o.sphere.radius)
    o.sphere = tight;
  return o;
}

}  // namespace

std::vector<SharpObject> find_sharp_objects(const SceneDesc &desc, const GeometryScene &geometry,
                                            const std::vector<Bsdf> &bsdfs) {
  std::vector<SharpObject> out;
  for (const ShapeRecord &s : geometry.shapes()) {
    if (!(s.area > 0) || s.material >= bsdfs.size()) continue;
    const Bsdf &b = bsdfs[s.material];
    if (b.lobes() & NIMBUS_LOBE_DIFFUSE) continue;
    const bool textured = !desc.materials[s.material].roughness_texture.empty();
    SharpObject o = shape_bounds(s);
    if (o.sphere.empty()) continue;
    o.min_alpha = textured ? 0.0f : b.min_alpha();
    out.push_back(o);
  }
  return out;
}

}  // namespace nimbus
