// The scene query's one-call segments (SDK 1.10): trace_from is spawn_ray, intersect_at and
// interaction_at, and occluded_to is spawn_ray_to and occluded_at, bit for bit, in a still scene and a
// moving one (triangles, spheres, disks), each counting one ray; the SDK kit makes the separate calls on a
// host without them. A mismatch in any byte of any record fails.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <random>

#include <nimbus/cpp/path_services.hpp>

#include "abi/run_state.hpp"
#include "query_world.hpp"

namespace nimbus {
namespace trace_from_test {

// The objects, still or moving while a shutter is open.
std::string scene(bool moving) {
  const char *box_motion = moving ? R"(
    motion: [{ time: 0, rotate: [0, 0, 0], translate: [1, 0, 0.5] },
             { time: 1, rotate: [0, 0, 120], translate: [1, 0.2, 0.8] }])"
                                  : "";
  const char *ball_motion =
      moving ? ",\n      motion: [{ time: 0, translate: [0, 0, 0] }, { time: 1, translate: [0.5, 0.8, 0] }]"
             : "";
  return std::string(R"(
camera: { position: [0, -6, 2], look_at: [0, 0, 0.5])") +
         (moving ? ", shutter: { open: 0, close: 1 }" : "") + R"( }
materials:
  floor: { type: diffuse, albedo: [0.5, 0.5, 0.5] }
  glass: { type: dielectric, ior: 1.5 }
objects:
  - { shape: rectangle, size: [10, 10], material: floor }
  - shape: box
    size: [1.4, 0.3, 0.5]
    material: glass)" +
         box_motion + R"(
  - { shape: sphere, center: [-2, 1, 0.4], radius: 0.4, material: glass }
  - { shape: disk, radius: 0.7, material: floor, transform: { rotate: [80, 0, 0], translate: [0, 2, 1] } }
  - { shape: sphere, center: [-1, -1, 0.3], radius: 0.3, material: floor)" +
         ball_motion + R"( }
lights:
  - { type: point, position: [0, 0, 4], intensity: [10, 10, 10] }
)";
}

template <class T>
bool same_bytes(const T &a, const T &b) {
  return std::memcmp(&a, &b, sizeof(T)) == 0;
}

// Surface points found by random rays into the scene, each with the time it was found at.
struct Vertex {
  nimbus_interaction_t ix;
  float time;
};

class TraceFrom : public ::testing::TestWithParam<bool> {
 protected:
  void SetUp() override {
    ASSERT_TRUE(w_.query);
    ASSERT_TRUE(NIMBUS_HAS_MEMBER(w_.query, nimbus_host_scene_query_v1_t, occluded_to));
    services_ = std::make_unique<HostServices>(w_.world.get(), &run_);
    ctx_.struct_size = sizeof(ctx_), ctx_.worker_index = 0, ctx_.worker_count = 1;
  }
  const nimbus_host_t *h() const { return services_->host(); }
  uint64_t rays() const { return run_.rays_traced(); }
  Vec3f random_direction() {
    for (;;) {
      const Vec3f d(u_(rng_) * 2 - 1, u_(rng_) * 2 - 1, u_(rng_) * 2 - 1);
      if (length_squared(d) > 0.01f && length_squared(d) <= 1) return normalize(d);
    }
  }
  // n surface points, from rays leaving random points above the floor.
  std::vector<Vertex> vertices(int n) {
    std::vector<Vertex> out;
    while (int(out.size()) < n) {
      nimbus_ray_t ray{};
      Vec3f(u_(rng_) * 6 - 3, u_(rng_) * 6 - 3, 0.1f + u_(rng_) * 2).store(ray.org);
      random_direction().store(ray.dir);
      ray.tfar = kInfinity, ray.mask = ~0u;
      const float time = u_(rng_);
      nimbus_hit_t hit;
      w_.query->intersect_at(h(), nullptr, &ray, &time, &hit, 1);
      if (hit.geom_id == NIMBUS_NONE) continue;
      Vertex v{{}, time};
      w_.query->interaction_at(h(), &ray, &hit, time, &v.ix);
      out.push_back(v);
    }
    return out;
  }

  const QueryWorld w_{scene(GetParam())};
  RunState run_{4, 4, 1, 1};
  std::unique_ptr<HostServices> services_;
  nimbus_thread_ctx_t ctx_{};
  std::mt19937 rng_{11};
  std::uniform_real_distribution<float> u_{0.0f, 1.0f};
};

TEST_P(TraceFrom, IsSpawnIntersectAndInteractionBitForBit) {
  int misses = 0, hits[5] = {0, 0, 0, 0, 0};
  for (const Vertex &v : vertices(6000)) {
    float dir[3];
    random_direction().store(dir);
    nimbus_ray_t ray;
    nimbus_hit_t hit;
    nimbus_interaction_t ix;
    std::memset(&ix, 0xA5, sizeof(ix));
    w_.query->spawn_ray(h(), &v.ix, dir, kInfinity, &ray);
    w_.query->intersect_at(h(), nullptr, &ray, &v.time, &hit, 1);
    if (hit.geom_id != NIMBUS_NONE) w_.query->interaction_at(h(), &ray, &hit, v.time, &ix);

    nimbus_ray_t fused_ray;
    nimbus_hit_t fused_hit;
    nimbus_interaction_t fused_ix;
    std::memset(&fused_ix, 0xA5, sizeof(fused_ix));  // a miss leaves it as it was
    const uint64_t before = rays();
    w_.query->trace_from(h(), &ctx_, &v.ix, dir, v.time, &fused_ray, &fused_hit, &fused_ix);
    ASSERT_EQ(rays(), before + 1);
    ASSERT_TRUE(same_bytes(ray, fused_ray));
    ASSERT_TRUE(same_bytes(hit, fused_hit));
    ASSERT_TRUE(same_bytes(ix, fused_ix));
    (hit.geom_id == NIMBUS_NONE ? misses : hits[std::min(hit.geom_id, 4u)])++;

    // The next vertex written over the one the ray leaves, and no ray asked for.
    nimbus_interaction_t in_place = v.ix;
    w_.query->trace_from(h(), &ctx_, &in_place, dir, v.time, nullptr, &fused_hit, &in_place);
    ASSERT_TRUE(same_bytes(hit, fused_hit));
    ASSERT_TRUE(same_bytes(hit.geom_id == NIMBUS_NONE ? v.ix : ix, in_place));
  }
  for (int shape = 0; shape < 5; ++shape) EXPECT_GT(hits[shape], 10) << "shape " << shape;
  EXPECT_GT(misses, 100);
}

TEST_P(TraceFrom, OccludedToIsSpawnRayToAndOccludedBitForBit) {
  const std::vector<Vertex> from = vertices(2000), to = vertices(2000);
  int blocked = 0, open = 0;
  for (size_t i = 0; i < from.size(); ++i) {
    for (const bool to_infinity : {false, true}) {
      nimbus_ray_t ray;
      w_.query->spawn_ray_to(h(), &from[i].ix, to[i].ix.p, &ray);
      if (to_infinity) ray.tfar = kInfinity;
      uint8_t expected = 2;
      w_.query->occluded_at(h(), nullptr, &ray, &from[i].time, &expected, 1);
      const uint64_t before = rays();
      const uint8_t got =
          w_.query->occluded_to(h(), &ctx_, &from[i].ix, to[i].ix.p, to_infinity ? 1 : 0, from[i].time);
      ASSERT_EQ(rays(), before + 1);
      ASSERT_EQ(got, expected);
      (got ? blocked : open)++;
    }
  }
  EXPECT_GT(blocked, 500);
  EXPECT_GT(open, 500);
}

// A plugin built with SDK 1.10 on an older host: the kit's TimedScene makes the separate calls instead,
// with the same results.
TEST_P(TraceFrom, KitFallsBackToSeparateCallsOnOlderHosts) {
  nimbus_host_scene_query_v1_t older = *w_.query;
  older.struct_size = offsetof(nimbus_host_scene_query_v1_t, trace_from);
  const auto *camera =
      static_cast<const nimbus_host_camera_v1_t *>(h()->get_service(h(), NIMBUS_SERVICE_CAMERA, 1));
  const auto *lights =
      static_cast<const nimbus_host_lights_v1_t *>(h()->get_service(h(), NIMBUS_SERVICE_LIGHTS, 1));
  const sdk::TimedScene fused = sdk::TimedScene::of(h(), w_.query, camera, lights);
  const sdk::TimedScene separate = sdk::TimedScene::of(h(), &older, camera, lights);
  ASSERT_TRUE(fused.fused);
  ASSERT_FALSE(separate.fused);
  ASSERT_EQ(fused.timed, GetParam());
  ASSERT_EQ(separate.timed, GetParam());
  const std::vector<Vertex> from = vertices(1000), to = vertices(1000);
  int hits = 0;
  for (size_t i = 0; i < from.size(); ++i) {
    const float time = fused.timed ? from[i].time : 0.0f;
    float dir[3];
    random_direction().store(dir);
    nimbus_hit_t hit[2];
    nimbus_interaction_t ix[2];
    std::memset(ix, 0, sizeof(ix));
    fused.trace_from(h(), ctx_, from[i].ix, dir, time, hit[0], ix[0]);
    separate.trace_from(h(), ctx_, from[i].ix, dir, time, hit[1], ix[1]);
    ASSERT_TRUE(same_bytes(hit[0], hit[1]));
    ASSERT_TRUE(same_bytes(ix[0], ix[1]));
    hits += hit[0].geom_id != NIMBUS_NONE;
    for (const bool to_infinity : {false, true})
      ASSERT_EQ(fused.occluded_to(h(), ctx_, from[i].ix, to[i].ix.p, to_infinity, time),
                separate.occluded_to(h(), ctx_, from[i].ix, to[i].ix.p, to_infinity, time));
  }
  EXPECT_GT(hits, 50);
}

INSTANTIATE_TEST_SUITE_P(StillAndMoving, TraceFrom, ::testing::Bool());

}  // namespace trace_from_test
}  // namespace nimbus
