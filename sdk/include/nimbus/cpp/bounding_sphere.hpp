// A sphere enclosing a point set (Ritter 1990: an initial sphere on two far-apart points, grown to
// take in every point outside it). Within ~5-20 % of the smallest enclosing sphere for typical sets,
// and always enclosing: the caustics solver aims photons at it, so a point outside would lose its
// photons. Linear time, no allocation.
#pragma once

#include <span>

#include <nimbus/cpp/math.hpp>

namespace nimbus {

struct Sphere {
  Vec3f center;
  float radius = -1;  // < 0: empty
  bool empty() const { return radius < 0; }
};

inline Sphere ritter_bounding_sphere(std::span<const Vec3f> points) {
  if (points.empty()) return {};
  const auto farthest = [&](const Vec3f &from) {
    size_t best = 0;
    float best_d2 = -1;
    for (size_t i = 0; i < points.size(); ++i)
      if (const float d2 = length_squared(points[i] - from); d2 > best_d2) best_d2 = d2, best = i;
    return points[best];
  };
  const Vec3f a = farthest(points[0]), b = farthest(a);
  Sphere s{(a + b) * 0.5f, 0.5f * length(b - a)};
  for (const Vec3f &p : points) {
    const float d = length(p - s.center);
    if (d <= s.radius) continue;
    const float r = 0.5f * (s.radius + d);
    s.center = s.center + (p - s.center) * ((r - s.radius) / d);
    s.radius = r;
  }
  // Growing in float can leave a point a rounding error outside: widen by what the worst one misses.
  float worst = s.radius;
  for (const Vec3f &p : points) worst = std::max(worst, length(p - s.center));
  s.radius = worst;
  return s;
}

}  // namespace nimbus
