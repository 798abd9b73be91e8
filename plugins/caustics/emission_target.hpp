// The emission target (solver spec section 6.2): after the probe, photons aim at the bounding sphere of
// the sharp surfaces only (the emission disk for infinite lights, cones for finite ones; emitters.hpp),
// since most of a light's photons would otherwise pass every caustic-forming surface.
#pragma once

#include <vector>

#include <nimbus/cpp/bounding_sphere.hpp>
#include <nimbus/cpp/math.hpp>

#include "photon_tracer.hpp"

namespace nimbus::caustics {

struct EmissionTarget {
  Sphere sphere;
  Vec3f lo{kInfinity}, hi{-kInfinity};  // the box around its sharp vertices (the sun's rectangle)
  bool valid() const { return sphere.radius > 0; }
};

// The target from the probe's sharp vertices (bounds [lo, hi] over all chunks): the smaller of the
// sphere around their box and Ritter's sphere around the vertices themselves (a glass sphere's hits give
// its own sphere, not the box's, sqrt(3) larger), with a 5 % margin. Invalid when it would not be smaller
// than the scene.
inline EmissionTarget target_from_probe(const std::vector<PhotonChunk> &chunks, const Vec3f &lo,
                                        const Vec3f &hi, float scene_radius) {
  Sphere target{(lo + hi) * 0.5f, 0.5f * length(hi - lo)};
  bool complete = true;
  std::vector<Vec3f> points;
  for (const PhotonChunk &c : chunks) {
    complete = complete && !c.sharp_points_full;
    points.insert(points.end(), c.sharp_points.begin(), c.sharp_points.end());
  }
  if (complete)
    if (const Sphere tight = ritter_bounding_sphere(points); tight.radius < target.radius) target = tight;
  const float radius = target.radius * 1.05f + 1e-4f * scene_radius;
  if (!(radius < scene_radius)) return {};
  const Vec3f grow = (hi - lo) * 0.05f + Vec3f(1e-4f * scene_radius);
  return {{target.center, radius}, lo - grow, hi + grow};
}

}  // namespace nimbus::caustics
