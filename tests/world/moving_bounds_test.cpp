// The scene service's moving_bounds (SDK 1.9): the bounds of every object that moves while the shutter
// is open, in object order, and nothing else. Every point at which a ray meets a moving object, at any
// time of the shutter, lies inside both its box and its sphere (a spin of 170 degrees per key, whose
// sweep leaves the boxes of its keys, and a translation); a still scene reports none.
#include <gtest/gtest.h>

#include <random>

#include "query_world.hpp"

namespace nimbus {
namespace moving_bounds_test {

std::string scene(const char *shutter) {
  return std::string(R"(
camera: { position: [0, -6, 2], look_at: [0, 0, 0.5])") +
         shutter + R"( }
materials:
  floor: { type: diffuse, albedo: [0.5, 0.5, 0.5] }
  glass: { type: dielectric, ior: 1.5 }
objects:
  - { shape: rectangle, size: [10, 10], material: floor }
  - shape: box
    size: [1.4, 0.3, 0.5]
    material: glass
    motion: [{ time: 0, rotate: [0, 0, 0], translate: [1, 0, 0.5] },
             { time: 0.5, rotate: [0, 0, 170], translate: [1, 0, 0.5] },
             { time: 1, rotate: [0, 0, 340], translate: [1, 0.2, 0.8] }]
  - { shape: sphere, center: [-2, 1, 0.4], radius: 0.4, material: glass }
  - { shape: sphere, center: [-1, -1, 0.3], radius: 0.3, material: floor,
      motion: [{ time: 0, translate: [0, 0, 0] }, { time: 1, translate: [0.5, 0.8, 0] }] }
lights:
  - { type: point, position: [0, 0, 4], intensity: [10, 10, 10] }
)";
}

// The moving objects' records, through the scene query.
std::vector<nimbus_object_bounds_t> moving_bounds(const QueryWorld &w) {
  if (!w.query) return {};
  std::vector<nimbus_object_bounds_t> b(w.query->moving_bounds(w.host(), nullptr, 0));
  EXPECT_EQ(w.query->moving_bounds(w.host(), b.data(), uint32_t(b.size())), b.size());
  return b;
}

TEST(MovingBounds, EveryHitOfAMovingObjectAtAnyTimeLiesInsideItsBounds) {
  const QueryWorld s(scene(", shutter: { open: 0, close: 1 }"));
  ASSERT_TRUE(s.query);
  ASSERT_TRUE(NIMBUS_HAS_MEMBER(s.query, nimbus_host_scene_query_v1_t, moving_bounds));
  const std::vector<nimbus_object_bounds_t> b = moving_bounds(s);
  ASSERT_EQ(b.size(), 2u) << "the spinning box and the sliding ball";
  const uint32_t moving_id[2] = {1, 3};
  const Vec3f aim[2] = {Vec3f(1, 0.1f, 0.65f), Vec3f(-0.75f, -0.6f, 0.3f)};
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  uint32_t hits[2] = {0, 0};
  for (int i = 0; i < 40000; ++i) {
    const int k = i & 1;
    const float time = u(rng);
    const Vec3f dir = normalize(Vec3f(u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f));
    const Vec3f target = aim[k] + Vec3f(u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f) * 1.6f;
    nimbus_ray_t ray{};
    (target - dir * 5.0f).store(ray.org), dir.store(ray.dir);
    ray.tfar = kInfinity, ray.mask = ~0u;
    nimbus_hit_t hit{};
    s.world->geometry->intersect(ray, hit, time);
    if (hit.geom_id != moving_id[k]) continue;
    ++hits[k];
    const Vec3f p = Vec3f::load(ray.org) + dir * hit.t;
    for (int a = 0; a < 3; ++a) {
      ASSERT_LE(b[k].lo[a], p[a] + 1e-5f) << "object " << k << " at time " << time;
      ASSERT_GE(b[k].hi[a], p[a] - 1e-5f) << "object " << k << " at time " << time;
    }
    ASSERT_LE(length(p - Vec3f::load(b[k].center)), b[k].radius * 1.0001f) << "object " << k;
  }
  EXPECT_GT(hits[0], 2000u);
  EXPECT_GT(hits[1], 1000u);
  // The spin sweeps a disc of radius 0.76 (the box's half diagonal in the plane) around its axis.
  EXPECT_LT(b[0].lo[0], 1 - 0.75f);
  EXPECT_GT(b[0].hi[1], 0.2f + 0.75f);
  // The ball: from (-1, -1) to (-0.5, -0.2), radius 0.3 (its box, padded by a sample's step).
  EXPECT_LE(b[1].lo[0], -1.3f);
  EXPECT_GT(b[1].lo[0], -1.4f);
  EXPECT_GE(b[1].hi[1], 0.1f);
  EXPECT_LT(b[1].hi[1], 0.2f);
}

TEST(MovingBounds, CountIsReturnedWhateverTheCapacity) {
  const QueryWorld s(scene(", shutter: { open: 0, close: 1 }"));
  ASSERT_TRUE(s.query);
  nimbus_object_bounds_t one{};
  EXPECT_EQ(s.query->moving_bounds(s.host(), &one, 1), 2u);
  EXPECT_GT(one.radius, 0.7f);
}

TEST(MovingBounds, AStillSceneHasNone) {
  const QueryWorld s(R"(
camera: { position: [0, -6, 2], look_at: [0, 0, 0.5], shutter: { open: 0, close: 1 } }
materials: { white: { type: diffuse } }
objects: [ { shape: sphere, radius: 1, material: white } ]
lights: [ { type: point, position: [0, 0, 3], intensity: [1, 1, 1] } ]
)");
  EXPECT_EQ(moving_bounds(s).size(), 0u);
}

}  // namespace moving_bounds_test
}  // namespace nimbus
