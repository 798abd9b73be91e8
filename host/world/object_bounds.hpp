// World-space bounds of one object (shape) over the whole shutter: what the scene service reports for
// the objects that can form caustics (sharp_objects.hpp) and for those that move (moving_bounds), so
// that a plugin aiming photons at an object, or asking whether a segment could meet something that
// moves, never leaves out a place the object takes.
#pragma once

#include <vector>

#include <nimbus/cpp/bounding_sphere.hpp>

#include "geometry/geometry_scene.hpp"

namespace nimbus {

struct ObjectBounds {
  Vec3f lo, hi;   // the object's box
  Sphere sphere;  // and a sphere around it (the smaller of the box's and Ritter's when it rests)
};

// The shape's bounds at every time of the shutter: its resting bounds, or those of its sweep when it
// moves (rigid motion or deformation). An empty sphere when the shape has no geometry.
ObjectBounds object_bounds(const ShapeRecord &shape);

// The bounds of every shape that moves, in shape order (none when the shutter is instantaneous).
std::vector<ObjectBounds> find_moving_objects(const GeometryScene &geometry, bool instantaneous_shutter);

}  // namespace nimbus
