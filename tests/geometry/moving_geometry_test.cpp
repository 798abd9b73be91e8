// Moving meshes (Embree instances with time steps) and deforming ones (a vertex buffer per time step): a
// ray meets a mesh where it is at the ray's time, and the host's surface at that time lies where Embree
// hit it, for translations, rotations and scales together, and for vertices and normals between steps.
#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <tuple>

#include "abi/host_services.hpp"
#include "abi/run_state.hpp"
#include "geometry/geometry_scene.hpp"
#include "scene/mesh_builders.hpp"
#include "scene/scene_desc.hpp"
#include "world/world.hpp"

namespace nimbus {
namespace moving_geometry_test {

nimbus_ray_t ray_from(const Vec3f &o, const Vec3f &d) {
  nimbus_ray_t r{};
  o.store(r.org), normalize(d).store(r.dir);
  r.tnear = 0, r.tfar = kInfinity, r.mask = ~0u;
  return r;
}

// A unit cube (object space) moving through `keys` over the shutter [0, 1], beside a static floor.
SceneDesc moving_cube(const std::vector<MotionTransform::Key> &keys) {
  SceneDesc d;
  d.materials.push_back(MaterialDesc{});
  ShapeDesc cube;
  cube.type = ShapeType::Box;
  cube.mesh = box_mesh(Vec3f(1));
  cube.motion = std::make_shared<const MotionTransform>(keys, 0.0f, 1.0f);
  ShapeDesc floor;
  floor.type = ShapeType::Box;
  floor.mesh = box_mesh(Vec3f(20, 20, 0.1f));
  for (Vec3f &p : floor.mesh.positions) p.z -= 3;
  d.shapes = {cube, floor};
  return d;
}

// A ray at a random time from `distance` away from `centre` towards a random point within `spread` of it
// (per coordinate), and what it met then: hit.geom_id 0 is the cube, whose surface ix then holds.
struct CubeShot {
  float time = 0;
  Vec3f origin;
  nimbus_ray_t ray{};
  nimbus_hit_t hit{};
  nimbus_interaction_t ix{};
};
CubeShot shoot_at(const GeometryScene &g, std::mt19937 &rng, const Vec3f &centre, float spread,
                  float distance) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  CubeShot s;
  s.time = u(rng);
  const Vec3f target = centre + Vec3f{u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f} * (2 * spread);
  s.origin = centre + normalize(Vec3f(u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f)) * distance;
  s.ray = ray_from(s.origin, target - s.origin);
  g.intersect(s.ray, s.hit, s.time);
  if (s.hit.geom_id == 0) g.interaction(s.ray, s.hit, s.ix, s.time);
  return s;
}

TEST(MovingGeometry, RaysMeetTheMeshWhereItIsAtTheirTime) {
  // The cube's centre moves from x = 0 to x = 2: it covers x = 2 from t = 0.75 on.
  const SceneDesc d = moving_cube({{0.0f, Transform{}}, {1.0f, Transform::translate({2, 0, 0})}});
  auto g = GeometryScene::build(d);
  ASSERT_TRUE(g.ok()) << g.error().message;
  EXPECT_TRUE((*g)->moves());
  const nimbus_ray_t ray = ray_from({2, -5, 0}, {0, 1, 0});
  nimbus_hit_t hit{};
  (*g)->intersect(ray, hit, 0.5f);
  EXPECT_EQ(hit.geom_id, NIMBUS_NONE);
  EXPECT_FALSE((*g)->occluded(ray, 0.5f));
  (*g)->intersect(ray, hit, 0.9f);
  ASSERT_EQ(hit.geom_id, 0u);
  EXPECT_NEAR(hit.t, 4.5f, 1e-4f);
  EXPECT_TRUE((*g)->occluded(ray, 0.9f));
  // The static floor is met at every time, and the bounds cover the sweep.
  const nimbus_ray_t down = ray_from({8, 8, 0}, {0, 0, -1});
  for (float t : {0.0f, 0.3f, 1.0f}) {
    (*g)->intersect(down, hit, t);
    EXPECT_EQ(hit.geom_id, 1u);
  }
  EXPECT_GE((*g)->bounds_max().x, 10.0f);
  EXPECT_NEAR((*g)->bounds_min().z, -3.05f, 1e-4f);
}

TEST(MovingGeometry, SurfaceAtTheRaysTimeIsWhereEmbreeHitIt) {
  // Translation, a half turn in two keys about a tilted axis, and growth, keys unevenly spaced.
  const Vec3f axis = normalize(Vec3f(0.3f, 0.2f, 1));
  const SceneDesc d =
      moving_cube({{0.0f, Transform{}},
                   {0.3f, Transform::translate({0.5f, 0, 0.2f}) * Transform::rotate(80, axis)},
                   {1.0f, Transform::translate({1, 0.5f, 0}) * Transform::rotate(170, axis) *
                              Transform::scale({1.5f, 1, 0.8f})}});
  auto g = GeometryScene::build(d);
  ASSERT_TRUE(g.ok()) << g.error().message;
  std::mt19937 rng(11);
  int hits = 0;
  for (int i = 0; i < 2000; ++i) {
    const CubeShot shot = shoot_at(**g, rng, Vec3f(0.5f, 0.25f, 0), 0.5f, 6);
    if (shot.hit.geom_id != 0) continue;
    ++hits;
    const float time = shot.time;
    const nimbus_interaction_t &ix = shot.ix;
    // Embree interpolates with approximate trigonometry: 1e-4 of a unit cube 6 units away is ~100 times
    // the float rounding of the hit and still ~1/100 of a pixel footprint at any usual resolution.
    const Vec3f along = shot.origin + Vec3f::load(shot.ray.dir) * shot.hit.t;
    EXPECT_LT(length(Vec3f::load(ix.p) - along), 1e-4f) << "time " << time;
    EXPECT_NEAR(length(Vec3f::load(ix.ng)), 1.0f, 1e-4f);
    EXPECT_TRUE(ix.flags & NIMBUS_IX_FRONT_FACE) << "rays from outside meet the outside";
  }
  EXPECT_GT(hits, 500);
}

// A ray leaving a moving surface never meets it again at its own origin. The host carries the surface
// point to world space with Embree's interpolated transform and bounds the rounding of Embree's way
// back to object space and of its approximate slerp in the offset distance; with the offset of a static
// surface, about one ray in a hundred leaving a turning block refracts at the same point again (each
// time gaining the radiance scale of a refraction: fireflies on motion-blurred glass).
TEST(MovingGeometry, RaysLeavingAMovingSurfaceDoNotMeetItAgain) {
  const Vec3f axis = normalize(Vec3f(0.3f, 0.2f, 1));
  for (const float scale : {0.07f, 1.0f, 30.0f}) {
    const SceneDesc d =
        moving_cube({{0.0f, Transform::scale(Vec3f(scale))},
                     {0.4f, Transform::translate(Vec3f(0.5f, 0, 0.2f) * scale) * Transform::rotate(80, axis) *
                                Transform::scale(Vec3f(scale))},
                     {1.0f, Transform::translate(Vec3f(1, 0.5f, 0) * scale) * Transform::rotate(170, axis) *
                                Transform::scale(Vec3f(scale))}});
    auto g = GeometryScene::build(d);
    ASSERT_TRUE(g.ok()) << g.error().message;
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const auto random_dir = [&] { return normalize(Vec3f(u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f)); };
    int hits = 0, outward_again = 0, inward_same_face = 0;
    for (int i = 0; i < 20000; ++i) {
      const CubeShot shot = shoot_at(**g, rng, Vec3f(0.5f, 0.25f, 0) * scale, 0.4f * scale, 6 * scale);
      if (shot.hit.geom_id != 0) continue;
      ++hits;
      const float time = shot.time;
      const nimbus_interaction_t &ix = shot.ix;
      const Vec3f p = Vec3f::load(ix.p), ng = Vec3f::load(ix.ng);
      for (const float side : {1.0f, -1.0f}) {
        Vec3f dir = random_dir();
        if (dot(dir, ng) * side < 0) dir = -dir;
        nimbus_ray_t leave = ray_from(offset_origin(p, ng, ix.eps, dir), dir);
        nimbus_hit_t next{};
        (*g)->intersect(leave, next, time);
        if (side > 0) {
          outward_again += next.geom_id == 0;  // a convex block: nothing of it lies outside its faces
        } else if (next.geom_id == 0) {
          nimbus_interaction_t far{};
          (*g)->interaction(leave, next, far, time);
          inward_same_face += dot(Vec3f::load(far.ng), ng) > 0.999f;
        }
      }
    }
    EXPECT_GT(hits, 5000) << "scale " << scale;
    EXPECT_EQ(outward_again, 0) << "of " << hits << " rays leaving outwards, scale " << scale;
    EXPECT_EQ(inward_same_face, 0) << "of " << hits << " rays leaving inwards, scale " << scale;
  }
}

TEST(MovingGeometry, OneKeyHoldsStill) {
  // A single key places the object-space mesh and nothing moves.
  SceneDesc d = moving_cube({{0.0f, Transform::translate({1, 0, 0})}});
  auto g = GeometryScene::build(d);
  ASSERT_TRUE(g.ok());
  EXPECT_FALSE((*g)->moves());
  nimbus_hit_t hit{};
  (*g)->intersect(ray_from({1.4f, -5, 0}, {0, 1, 0}), hit, 0.7f);
  EXPECT_EQ(hit.geom_id, 0u);
  EXPECT_NEAR(hit.t, 4.5f, 1e-4f);
}

// Analytic shapes move as instances too: a sphere of radius 0.5 (object space) sliding from x = 0 to x = 2
// and growing 1.5 times, and a disk turning about x, are met where they are at the ray's time, with
// their surfaces computed in object space and carried back.
TEST(MovingGeometry, SpheresAndDisksMoveAsWell) {
  SceneDesc d;
  d.materials.push_back(MaterialDesc{});
  ShapeDesc ball;
  ball.type = ShapeType::Sphere, ball.radius = 0.5f;
  ball.motion = std::make_shared<const MotionTransform>(
      std::vector<MotionTransform::Key>{
          {0.0f, Transform{}}, {1.0f, Transform::translate({2, 0, 0}) * Transform::scale(Vec3f(1.5f))}},
      0.0f, 1.0f);
  ShapeDesc disk;
  disk.type = ShapeType::Disk, disk.radius = 1, disk.normal = {0, 0, 1};
  disk.motion = std::make_shared<const MotionTransform>(
      std::vector<MotionTransform::Key>{
          {0.0f, Transform::translate({0, 5, 0})},
          {1.0f, Transform::translate({0, 5, 0}) * Transform::rotate(90, {1, 0, 0})}},
      0.0f, 1.0f);
  d.shapes = {ball, disk};
  auto g = GeometryScene::build(d);
  ASSERT_TRUE(g.ok()) << g.error().message;
  for (const float time : {0.0f, 0.25f, 0.5f, 1.0f}) {
    const Vec3f centre(2 * time, 0, 0);
    const float radius = 0.5f * (1 + 0.5f * time);
    const nimbus_ray_t ray = ray_from(centre + Vec3f(0.2f * radius, -5, 0.1f * radius), {0, 1, 0});
    nimbus_hit_t hit{};
    (*g)->intersect(ray, hit, time);
    ASSERT_EQ(hit.geom_id, 0u) << "time " << time;
    nimbus_interaction_t ix{};
    (*g)->interaction(ray, hit, ix, time);
    const Vec3f p = Vec3f::load(ix.p);
    EXPECT_NEAR(length(p - centre), radius, 1e-5f) << "time " << time;
    EXPECT_NEAR(dot(Vec3f::load(ix.ng), normalize(p - centre)), 1.0f, 1e-5f);
    EXPECT_LT(length(p - (Vec3f::load(ray.org) + Vec3f::load(ray.dir) * hit.t)), 1e-4f);
    EXPECT_TRUE(ix.flags & NIMBUS_IX_FRONT_FACE);
  }
  // The disk faces +z at time 0 (a ray down meets it) and -y after its quarter turn (a ray along +y does).
  nimbus_hit_t hit{};
  (*g)->intersect(ray_from({0.3f, 5.2f, 4}, {0, 0, -1}), hit, 0.0f);
  EXPECT_EQ(hit.geom_id, 1u);
  (*g)->intersect(ray_from({0.3f, 5.2f, 4}, {0, 0, -1}), hit, 1.0f);
  EXPECT_EQ(hit.geom_id, NIMBUS_NONE);
  const nimbus_ray_t along_y = ray_from({0.3f, 0, 0.2f}, {0, 1, 0});
  (*g)->intersect(along_y, hit, 1.0f);
  ASSERT_EQ(hit.geom_id, 1u);
  nimbus_interaction_t ix{};
  (*g)->interaction(along_y, hit, ix, 1.0f);
  EXPECT_NEAR(ix.p[1], 5.0f, 1e-5f);
  EXPECT_NEAR(std::abs(ix.ng[1]), 1.0f, 1e-5f);
}

// A deforming quad (deformation blur): vertex buffers at three evenly spaced times over the shutter
// [1, 3], rising from z = 0 to z = 1 and back, its normals tilting from +z towards +x and back.
TEST(MovingGeometry, DeformingMeshIsWhereItsStepsPutItAtTheRaysTime) {
  SceneDesc d;
  d.materials.push_back(MaterialDesc{});
  ShapeDesc quad;
  quad.type = ShapeType::Mesh;
  quad.mesh.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  quad.mesh.normals.assign(4, Vec3f(0, 0, 1));
  quad.mesh.indices = {0, 1, 2, 0, 2, 3};
  const auto lifted = [&](float z) {
    std::vector<Vec3f> p = quad.mesh.positions;
    for (Vec3f &q : p) q.z = z;
    return p;
  };
  quad.mesh.position_steps = {lifted(0), lifted(1), lifted(0)};
  const Vec3f tilted = normalize(Vec3f(1, 0, 1));
  quad.mesh.normal_steps = {std::vector<Vec3f>(4, Vec3f(0, 0, 1)), std::vector<Vec3f>(4, tilted),
                            std::vector<Vec3f>(4, Vec3f(0, 0, 1))};
  quad.mesh.steps_open = 1, quad.mesh.steps_close = 3;
  d.shapes = {quad};
  auto g = GeometryScene::build(d);
  ASSERT_TRUE(g.ok()) << g.error().message;
  EXPECT_TRUE((*g)->moves());
  EXPECT_NEAR((*g)->bounds_max().z, 1.0f, 1e-6f);
  const nimbus_ray_t down = ray_from({0.3f, 0.2f, 5}, {0, 0, -1});
  for (const auto &[time, z, tilt] : {std::tuple{1.0f, 0.0f, 0.0f},
                                      {1.5f, 0.5f, 0.5f},
                                      {2.0f, 1.0f, 1.0f},
                                      {2.5f, 0.5f, 0.5f},
                                      {3.0f, 0.0f, 0.0f}}) {
    nimbus_hit_t hit{};
    (*g)->intersect(down, hit, time);
    ASSERT_EQ(hit.geom_id, 0u) << "time " << time;
    EXPECT_NEAR(hit.t, 5 - z, 1e-5f) << "time " << time;
    nimbus_interaction_t ix{};
    (*g)->interaction(down, hit, ix, time);
    EXPECT_NEAR(ix.p[2], z, 1e-5f) << "time " << time;
    const Vec3f ns = normalize(Vec3f(0, 0, 1) * (1 - tilt) + tilted * tilt);
    EXPECT_NEAR(dot(Vec3f::load(ix.ns), ns), 1.0f, 1e-5f) << "time " << time;
    EXPECT_NEAR(ix.ng[2], 1.0f, 1e-6f);
  }
}

// Through the C ABI (SDK 1.7): the scene query takes each ray's time, and the camera reports the
// shutter, what moves, and draws times from the shutter's curve.
TEST(MovingGeometry, SceneQueryAndCameraServicesCarryTime) {
  SceneDesc d = moving_cube({{0.0f, Transform{}}, {1.0f, Transform::translate({2, 0, 0})}});
  d.camera.shutter = Shutter(0.0f, 1.0f);
  auto world = World::build(d, FilterType::Box);
  ASSERT_TRUE(world.ok()) << world.error().message;
  RunState run(4, 4, 1, 1);
  HostServices services(world->get(), &run);
  const nimbus_host_t *h = services.host();
  const auto *query =
      static_cast<const nimbus_host_scene_query_v1_t *>(h->get_service(h, NIMBUS_SERVICE_SCENE_QUERY, 1));
  const auto *camera =
      static_cast<const nimbus_host_camera_v1_t *>(h->get_service(h, NIMBUS_SERVICE_CAMERA, 1));
  ASSERT_TRUE(NIMBUS_HAS_MEMBER(query, nimbus_host_scene_query_v1_t, interaction_at));
  ASSERT_TRUE(NIMBUS_HAS_MEMBER(camera, nimbus_host_camera_v1_t, sample_time));
  const nimbus_ray_t rays[2] = {ray_from({2, -5, 0}, {0, 1, 0}), ray_from({2, -5, 0}, {0, 1, 0})};
  const float times[2] = {0.5f, 0.9f};
  nimbus_hit_t hits[2];
  query->intersect_at(h, nullptr, rays, times, hits, 2);
  EXPECT_EQ(hits[0].geom_id, NIMBUS_NONE);
  ASSERT_EQ(hits[1].geom_id, 0u);
  uint8_t blocked[2];
  query->occluded_at(h, nullptr, rays, times, blocked, 2);
  EXPECT_EQ(blocked[0], 0);
  EXPECT_EQ(blocked[1], 1);
  nimbus_interaction_t ix{};
  query->interaction_at(h, &rays[1], &hits[1], 0.9f, &ix);
  EXPECT_NEAR(ix.p[1], -0.5f, 1e-5f);
  EXPECT_NEAR(ix.ng[1], -1.0f, 1e-5f);
  float open = -1, close = -1, pdf = 0;
  EXPECT_EQ(camera->shutter(h, &open, &close), NIMBUS_MOTION_GEOMETRY);
  EXPECT_EQ(open, 0.0f);
  EXPECT_EQ(close, 1.0f);
  const float t = camera->sample_time(h, 0.25f, &pdf);
  EXPECT_NEAR(t, 0.25f, 1e-6f);
  EXPECT_NEAR(pdf, 1.0f, 1e-6f);
  // A shutter that opens and closes at once: nothing moves for the camera, times are its open time.
  d.camera.shutter = Shutter(0.5f, 0.5f);
  auto still = World::build(d, FilterType::Box);
  ASSERT_TRUE(still.ok());
  HostServices still_services(still->get(), &run);
  const nimbus_host_t *hs = still_services.host();
  EXPECT_EQ(camera->shutter(hs, &open, &close), 0u);
  EXPECT_EQ(camera->sample_time(hs, 0.7f, &pdf), 0.5f);
  EXPECT_EQ(pdf, 1.0f);
}

}  // namespace moving_geometry_test
}  // namespace nimbus
