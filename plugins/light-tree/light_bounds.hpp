// Spatial and directional bounds of a set of emitters and the importance of such a set for a receiving
// point (Conty Estevez & Kulla 2018, "Importance Sampling of Many Lights with Adaptive Tree Splitting",
// in the formulation of pbrt-v4's LightBounds).
#pragma once

#include <nimbus/lights.h>

#include <nimbus/cpp/math.hpp>

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

// Four sibling subtrees' bounds side by side, as traversal reads them: one SIMD evaluation gives the
// importance of all four for a receiving point, so a sample walks ~7 levels of 4-wide nodes for 10,000
// lights instead of 14 binary levels with two scalar evaluations each. The centroid, radius and cone sine
// that importance needs are computed once when the tree is built. Empty lanes have zero power.
struct WideNode {
  static constexpr int kWidth = 4;
  // Sets lane k to the bounds b (of a light when leaf, else of the wide node `child`).
  void set(int k, const LightBounds &b, uint32_t child, bool leaf);
  // Importance of each lane for a receiver at p with normal n (zero vector: a point in a medium or
  // unknown): the power over the squared distance, times the bounds on the emitters' and the receiver's
  // cosines (Conty Estevez & Kulla 2018; pbrt-v4's LightBounds::Importance).
  void importance(const Vec3f &p, const Vec3f &n, float out[kWidth]) const;

  // Of the bounding box's circumscribed sphere (half its diagonal); the radius also floors the distance
  // term, as pbrt-v4 floors d^2 by half the diagonal.
  alignas(16) float cx[kWidth]{}, cy[kWidth]{}, cz[kWidth]{}, radius[kWidth]{}, radius2[kWidth]{};
  alignas(16) float ax[kWidth]{}, ay[kWidth]{}, az[kWidth]{}, cos_o[kWidth]{}, sin_o[kWidth]{},
      cos_e[kWidth]{};
  alignas(16) float phi[kWidth]{};
  alignas(16) int32_t two_sided[kWidth]{};  // all bits set when two-sided
  uint32_t child[kWidth]{};                 // light index (leaf lanes) or wide node index
  uint8_t leaf_mask = 0;                    // bit k: lane k is a light
};

// The bounds of one light, from the host's light info. Infinite lights have none (phi = 0).
LightBounds bounds_of(const nimbus_light_info_t &info);

}  // namespace nimbus::lights
