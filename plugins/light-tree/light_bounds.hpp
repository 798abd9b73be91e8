// Spatial and directional bounds of a set of emitters and the importance of such a set for a receiving
// point (Conty Estevez & Kulla 2018, "Importance Sampling of Many Lights with Adaptive Tree Splitting",
// in the formulation of pbrt-v4's LightBounds).
#pragma once

#include <nimbus/lights.h>

#include "core/math.hpp"

namespace nimbus::lights {

// A cone of directions: axis w and cos of its half angle (-1 = all directions, empty when w is zero).
struct DirectionCone {
  Vec3f w;
  float cos_theta = 1;
  bool empty() const { return is_black(w); }
  static DirectionCone sphere() { return {{0, 0, 1}, -1}; }
};

DirectionCone cone_union(const DirectionCone &a, const DirectionCone &b);

struct LightBounds {
  Vec3f lo{kInfinity}, hi{-kInfinity};
  float phi = 0;          // power
  DirectionCone normals;  // directions of the emitters' normals (cos_theta_o)
  float cos_theta_e = 1;  // how far beyond its normal an emitter emits
  bool two_sided = false;

  Vec3f centroid() const { return (lo + hi) * 0.5f; }
};

LightBounds bounds_union(const LightBounds &a, const LightBounds &b);

// LightBounds as the traversal reads them: the centroid, radius and cone sine that importance() needs are
// computed once when the tree is built, not at every node of every light sample (two importance
// evaluations per level, ~14 levels for 10,000 lights).
struct NodeBounds {
  NodeBounds() = default;
  explicit NodeBounds(const LightBounds &b);
  // Importance for a receiver at p with normal n (zero vector: a point in a medium or unknown).
  float importance(const Vec3f &p, const Vec3f &n) const;

  Vec3f centroid, axis;
  float phi = 0;
  // Of the bounding box's circumscribed sphere (half its diagonal). The radius also floors the distance
  // term, as pbrt-v4 floors d^2 by half the diagonal.
  float radius = 0, radius2 = 0;
  float cos_o = 1, sin_o = 0, cos_e = 1;
  bool two_sided = false;
};

// The bounds of one light, from the host's light info. Infinite lights have none (phi = 0).
LightBounds bounds_of(const nimbus_light_info_t &info);

}  // namespace nimbus::lights
