#include "world/object_bounds.hpp"

#include <algorithm>

namespace nimbus {
namespace {

// The shape's box and the smaller of the sphere around it and Ritter's sphere around its vertices, in
// the shape's own space (world space unless it moves rigidly).
ObjectBounds resting_bounds(const ShapeRecord &s) {
  ObjectBounds o;
  if (s.type == ShapeType::Sphere || s.type == ShapeType::Disk) {
    // A disk's box is its sphere's: a bound, and disks are rarely sharp.
    o.lo = s.center - Vec3f(s.radius), o.hi = s.center + Vec3f(s.radius);
    o.sphere = {s.center, s.radius};
    return o;
  }
  if (!s.mesh || s.mesh->positions.empty()) return o;
  o.lo = Vec3f(kInfinity), o.hi = Vec3f(-kInfinity);
  for (const Vec3f &p : s.mesh->positions) o.lo = min(o.lo, p), o.hi = max(o.hi, p);
  // A deforming mesh moves each vertex linearly between its shapes: their boxes bound it at every time.
  for (const std::vector<Vec3f> &step : s.mesh->position_steps)
    for (const Vec3f &p : step) o.lo = min(o.lo, p), o.hi = max(o.hi, p);
  o.sphere = {(o.lo + o.hi) * 0.5f, 0.5f * length(o.hi - o.lo)};
  if (!s.mesh->position_steps.empty()) return o;
  if (const Sphere tight = ritter_bounding_sphere(s.mesh->positions); tight.radius < o.sphere.radius)
    o.sphere = tight;
  return o;
}

// A rigidly moving shape's bounds over the whole shutter. Every point of the resting box is a convex
// combination of its corners, and so is its image under the transform at any time: the corners' images
// at dense times bound the sweep once padded by the largest step a corner takes between neighbouring
// samples.
ObjectBounds swept_bounds(const ObjectBounds &rest, const MotionTransform &motion) {
  const size_t samples = 8 * motion.steps().size() + 1;
  const float open = motion.open(), close = motion.close();
  ObjectBounds o = rest;
  o.lo = Vec3f(kInfinity), o.hi = Vec3f(-kInfinity);
  Vec3f previous[8];
  float pad = 0;
  for (size_t i = 0; i < samples; ++i) {
    const Transform m = motion.at(open + (close - open) * float(i) / float(samples - 1));
    for (int c = 0; c < 8; ++c) {
      const Vec3f q = m.point(
          Vec3f(c & 1 ? rest.hi.x : rest.lo.x, c & 2 ? rest.hi.y : rest.lo.y, c & 4 ? rest.hi.z : rest.lo.z));
      if (i > 0) pad = std::max(pad, length(q - previous[c]));
      o.lo = min(o.lo, q), o.hi = max(o.hi, q), previous[c] = q;
    }
  }
  o.lo -= Vec3f(pad), o.hi += Vec3f(pad);
  o.sphere = {(o.lo + o.hi) * 0.5f, 0.5f * length(o.hi - o.lo)};
  return o;
}

// Whether the shape moves while the shutter is open (rigidly or by deforming).
bool shape_moves(const ShapeRecord &shape) { return shape.motion || (shape.mesh && shape.mesh->deforms()); }

}  // namespace

ObjectBounds object_bounds(const ShapeRecord &shape) {
  const ObjectBounds rest = resting_bounds(shape);
  // A rigidly moving shape's geometry is in its own space: its bounds are those of its sweep.
  return shape.motion && !rest.sphere.empty() ? swept_bounds(rest, *shape.motion) : rest;
}

std::vector<ObjectBounds> find_moving_objects(const GeometryScene &geometry, bool instantaneous_shutter) {
  std::vector<ObjectBounds> out;
  if (instantaneous_shutter) return out;
  for (const ShapeRecord &s : geometry.shapes())
    if (shape_moves(s))
      if (const ObjectBounds b = object_bounds(s); !b.sphere.empty()) out.push_back(b);
  return out;
}

}  // namespace nimbus
