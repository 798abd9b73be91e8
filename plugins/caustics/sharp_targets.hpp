// What photon emission aims at (solver spec 6.2, projection maps): the bounds of every object that can
// form a caustic, as the host reports them (scene service sharp_bounds, SDK 1.3), merged into a few
// clusters so that a light's emission mixture and its density on the camera side stay cheap. Known at
// prepare, before any photon is traced: no sharp object can be missed because a probe did not meet it.
#pragma once

#include <nimbus/scene.h>

#include <algorithm>
#include <numeric>
#include <vector>

#include <nimbus/cpp/bounding_sphere.hpp>
#include <nimbus/cpp/math.hpp>

namespace nimbus::caustics {

// Clusters per scene: each finite light's emission is a mixture over them (spec 6.2), evaluated at every
// emitter hit and NEE sample of a camera path while a photon map is active.
inline constexpr size_t kMaxTargets = 8;
// Sharp objects whose own spheres are kept (for each light's share of power towards them); beyond it the
// clusters stand in.
inline constexpr size_t kMaxObjectSpheres = 4096;

struct Target {
  Sphere sphere;
  Vec3f lo{kInfinity}, hi{-kInfinity};
};

// The smallest sphere enclosing spheres a and b.
inline Sphere enclose(const Sphere &a, const Sphere &b) {
  if (a.empty()) return b;
  if (b.empty()) return a;
  const Vec3f d = b.center - a.center;
  const float len = length(d);
  if (len + b.radius <= a.radius) return a;
  if (len + a.radius <= b.radius) return b;
  const float r = 0.5f * (len + a.radius + b.radius);
  return {a.center + d * ((r - a.radius) / len), r};
}

// One target around `objects`: the union of their boxes, and the smaller of the sphere around that box
// and the spheres merged one by one.
inline Target enclose(const std::vector<Target> &objects) {
  Target t;
  Sphere merged;
  for (const Target &o : objects) {
    t.lo = min(t.lo, o.lo), t.hi = max(t.hi, o.hi);
    merged = enclose(merged, o.sphere);
  }
  const Sphere box{(t.lo + t.hi) * 0.5f, 0.5f * length(t.hi - t.lo)};
  t.sphere = merged.radius < box.radius ? merged : box;
  return t;
}

// Splits `objects` (sorted in place) into at most `k` groups by median cuts along the widest extent of
// their centres, ties by the host's order: the same clusters for the same scene.
inline void cluster(std::vector<Target> &objects, size_t k, std::vector<Target> &out) {
  if (objects.empty()) return;
  if (k <= 1 || objects.size() == 1) {
    out.push_back(enclose(objects));
    return;
  }
  Vec3f lo(kInfinity), hi(-kInfinity);
  for (const Target &o : objects) lo = min(lo, o.sphere.center), hi = max(hi, o.sphere.center);
  const Vec3f ext = hi - lo;
  const int axis = ext.x >= ext.y && ext.x >= ext.z ? 0 : (ext.y >= ext.z ? 1 : 2);
  std::stable_sort(objects.begin(), objects.end(), [&](const Target &a, const Target &b) {
    return a.sphere.center[axis] < b.sphere.center[axis];
  });
  const size_t k0 = k / 2, mid = std::max<size_t>(1, objects.size() * k0 / k);
  std::vector<Target> left(objects.begin(), objects.begin() + ptrdiff_t(mid));
  std::vector<Target> right(objects.begin() + ptrdiff_t(mid), objects.end());
  cluster(left, k0, out);
  cluster(right, k - k0, out);
}

struct SharpTargets {
  std::vector<Target> clusters;  // at most kMaxTargets
  Target all;                    // around every cluster (the emission disk of infinite lights)
  std::vector<Sphere> objects;   // each object's sphere, or none beyond kMaxObjectSpheres objects
  bool empty() const { return clusters.empty(); }
};

// The host's sharp objects (materials with a GGX alpha below `alpha_max` or delta lobes), clustered.
// Empty when the scene has none, or when the host predates SDK 1.3 (then photons are not aimed).
inline SharpTargets query_sharp_targets(const nimbus_host_t *h, const nimbus_host_scene_query_v1_t *scene,
                                        float alpha_max) {
  SharpTargets t;
  if (!NIMBUS_HAS_MEMBER(scene, nimbus_host_scene_query_v1_t, sharp_bounds)) return t;
  std::vector<nimbus_object_bounds_t> bounds(scene->sharp_bounds(h, alpha_max, nullptr, 0));
  bounds.resize(scene->sharp_bounds(h, alpha_max, bounds.data(), uint32_t(bounds.size())));
  std::vector<Target> objects;
  for (const nimbus_object_bounds_t &b : bounds)
    if (b.radius >= 0 && std::isfinite(b.radius))
      objects.push_back({{Vec3f::load(b.center), b.radius}, Vec3f::load(b.lo), Vec3f::load(b.hi)});
  if (objects.empty()) return t;
  if (objects.size() <= kMaxObjectSpheres)
    for (const Target &o : objects) t.objects.push_back(o.sphere);
  cluster(objects, kMaxTargets, t.clusters);
  t.all = enclose(t.clusters);
  return t;
}

}  // namespace nimbus::caustics
