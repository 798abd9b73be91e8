// Ray queries against analytic spheres, disks and boxes: distances, normals, grazing rays, and
// self-intersection when rays leave a surface (scene scales 1e-4 to 1e6).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>

#include "geometry/geometry_scene.hpp"
#include "scene/scene_desc.hpp"

namespace nimbus {
namespace ray_query_test {

MeshData box_mesh(const Vec3f &lo, const Vec3f &hi) {
  MeshData m;
  for (int i = 0; i < 8; ++i)
    m.positions.push_back({i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z});
  // Outward winding (right-handed): each face listed counter-clockwise seen from outside.
  const uint32_t f[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                            {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (auto &q : f) m.indices.insert(m.indices.end(), {q[0], q[1], q[2], q[0], q[2], q[3]});
  return m;
}

SceneDesc scene_with(std::vector<ShapeDesc> shapes) {
  SceneDesc d;
  d.materials.push_back(MaterialDesc{});
  d.shapes = std::move(shapes);
  return d;
}

ShapeDesc sphere(const Vec3f &c, float r) {
  ShapeDesc s;
  s.type = ShapeType::Sphere, s.center = c, s.radius = r;
  return s;
}

nimbus_ray_t make_ray(const Vec3f &o, const Vec3f &d, float tnear = 0, float tfar = kInfinity) {
  nimbus_ray_t r{};
  o.store(r.org), normalize(d).store(r.dir);
  r.tnear = tnear, r.tfar = tfar, r.mask = ~0u;
  return r;
}

TEST(RayQuery, SphereDistanceAndNormal) {
  const SceneDesc d = scene_with({sphere({0, 0, 0}, 1)});
  auto g = GeometryScene::build(d);
  ASSERT_TRUE(g.ok()) << g.error().message;
  nimbus_hit_t hit;
  (*g)->intersect(make_ray({0, 0, -5}, {0, 0, 1}), hit);
  ASSERT_EQ(hit.geom_id, 0u);
  EXPECT_NEAR(hit.t, 4.0f, 1e-5f);
  nimbus_interaction_t ix;
  (*g)->interaction(make_ray({0, 0, -5}, {0, 0, 1}), hit, ix);
  EXPECT_NEAR(ix.ng[2], -1.0f, 1e-6f);
  EXPECT_TRUE(ix.flags & NIMBUS_IX_FRONT_FACE);
  // A ray from inside hits the far side and sees the back face.
  (*g)->intersect(make_ray({0, 0, 0}, {1, 0, 0}), hit);
  ASSERT_EQ(hit.geom_id, 0u);
  EXPECT_NEAR(hit.t, 1.0f, 1e-6f);
  // A miss.
  (*g)->intersect(make_ray({0, 2, -5}, {0, 0, 1}), hit);
  EXPECT_EQ(hit.geom_id, NIMBUS_NONE);
}

TEST(RayQuery, GrazingRaysOnSphereSilhouette) {
  const SceneDesc d = scene_with({sphere({0, 0, 0}, 1)});
  auto g = GeometryScene::build(d);
  ASSERT_TRUE(g.ok());
  // Rays at perpendicular distance just inside / just outside the radius.
  for (float off : {0.999f, 0.99999f}) {
    nimbus_hit_t hit;
    (*g)->intersect(make_ray({off, 0, -10}, {0, 0, 1}), hit);
    EXPECT_EQ(hit.geom_id, 0u) << off;
    EXPECT_TRUE(std::isfinite(hit.t));
  }
  nimbus_hit_t hit;
  (*g)->intersect(make_ray({1.0001f, 0, -10}, {0, 0, 1}), hit);
  EXPECT_EQ(hit.geom_id, NIMBUS_NONE);
}

TEST(RayQuery, BoxHitsAllSixFacesWithOutwardNormals) {
  ShapeDesc b;
  b.type = ShapeType::Box;
  b.mesh = box_mesh({-1, -1, -1}, {1, 1, 1});
  const SceneDesc d = scene_with({b});  // the geometry references the meshes: keep them alive
  auto g = GeometryScene::build(d);
  ASSERT_TRUE(g.ok());
  const Vec3f dirs[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (const Vec3f &d : dirs) {
    const nimbus_ray_t r = make_ray(d * -5.0f + Vec3f(0.1f, 0.2f, 0.3f) * (Vec3f(1) - abs(d)), d);
    nimbus_hit_t hit;
    (*g)->intersect(r, hit);
    ASSERT_EQ(hit.geom_id, 0u);
    EXPECT_NEAR(hit.t, 4.0f, 1e-5f);
    nimbus_interaction_t ix;
    (*g)->interaction(r, hit, ix);
    EXPECT_NEAR(dot(Vec3f::load(ix.ng), d), -1.0f, 1e-5f) << "normal must point out, against the ray";
  }
  // Grazing: a ray along a face's plane, exactly on the edge, finds the box or misses, never NaN.
  nimbus_hit_t hit;
  (*g)->intersect(make_ray({-5, 1, 0}, {1, 0, 0}), hit);
  if (hit.geom_id != NIMBUS_NONE) {
    EXPECT_TRUE(std::isfinite(hit.t));
  }
}

// Rays spawned from a hit point, offset by the interaction's eps, must not hit the same surface again
// (no acne) and must reach the other side of a sphere when refracting inwards.
class SelfIntersection : public ::testing::TestWithParam<float> {};

TEST_P(SelfIntersection, SpawnedRaysLeaveTheSurface) {
  const float scale = GetParam();
  ShapeDesc b;
  b.type = ShapeType::Box;
  b.mesh = box_mesh(Vec3f(-1 * scale), Vec3f(1 * scale));
  for (Vec3f &p : b.mesh.positions) p += Vec3f(3 * scale, 0, 0);
  const SceneDesc d = scene_with({sphere({0, 0, 0}, scale), b});
  auto g = GeometryScene::build(d);
  ASSERT_TRUE(g.ok());
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> U(-1, 1);
  int acne = 0, tests = 0;
  for (int i = 0; i < 2000; ++i) {
    // Random ray from far away towards the sphere or box.
    const Vec3f target =
        (i % 2 ? Vec3f(0, 0, 0) : Vec3f(3 * scale, 0, 0)) + Vec3f(U(rng), U(rng), U(rng)) * (0.9f * scale);
    const Vec3f org = target + normalize(Vec3f(U(rng), U(rng), U(rng))) * (20 * scale);
    const nimbus_ray_t r = make_ray(org, target - org);
    nimbus_hit_t hit;
    (*g)->intersect(r, hit);
    if (hit.geom_id == NIMBUS_NONE) continue;
    nimbus_interaction_t ix;
    (*g)->interaction(r, hit, ix);
    const Vec3f p = Vec3f::load(ix.p), n = Vec3f::load(ix.ng);
    // Reflect: leaves on the outside; the closest hit must not be the same point.
    Vec3f out = normalize(n + Vec3f(U(rng), U(rng), U(rng)) * 0.99f);
    if (dot(out, n) <= 0) out = n;
    nimbus_ray_t r2 = make_ray(offset_origin(p, n, ix.eps, out), out);
    nimbus_hit_t h2;
    (*g)->intersect(r2, h2);
    ++tests;
    if (h2.geom_id == hit.geom_id && h2.t < 1e-3f * scale) ++acne;
    // Enter: the ray must find the far side, not the entry point.
    const Vec3f in = -n;
    nimbus_ray_t r3 = make_ray(offset_origin(p, n, ix.eps, in), in);
    nimbus_hit_t h3;
    (*g)->intersect(r3, h3);
    EXPECT_EQ(h3.geom_id, hit.geom_id);
    if (h3.geom_id == hit.geom_id) {
      EXPECT_GT(h3.t, 1e-3f * scale);
    }
  }
  EXPECT_GT(tests, 500);
  EXPECT_EQ(acne, 0);
}

INSTANTIATE_TEST_SUITE_P(Scales, SelfIntersection, ::testing::Values(1e-4f, 1.0f, 1e3f, 1e6f));

TEST(RayQuery, OccludedRespectsTfar) {
  const SceneDesc d = scene_with({sphere({0, 0, 0}, 1)});
  auto g = GeometryScene::build(d);
  ASSERT_TRUE(g.ok());
  EXPECT_TRUE((*g)->occluded(make_ray({0, 0, -5}, {0, 0, 1}, 0, 10)));
  EXPECT_FALSE((*g)->occluded(make_ray({0, 0, -5}, {0, 0, 1}, 0, 3.9f)));
  EXPECT_FALSE((*g)->occluded(make_ray({0, 0, -5}, {0, 0, -1}, 0, kInfinity)));
  // Inactive ray (tnear > tfar).
  EXPECT_FALSE((*g)->occluded(make_ray({0, 0, -5}, {0, 0, 1}, 2, 1)));
}

TEST(RayQuery, DiskHitInsideRadiusOnly) {
  ShapeDesc s;
  s.type = ShapeType::Disk, s.center = {0, 0, 1}, s.radius = 0.5f, s.normal = {0, 0, 1};
  const SceneDesc d = scene_with({s});
  auto g = GeometryScene::build(d);
  ASSERT_TRUE(g.ok());
  nimbus_hit_t hit;
  (*g)->intersect(make_ray({0.49f, 0, 0}, {0, 0, 1}), hit);
  EXPECT_EQ(hit.geom_id, 0u);
  EXPECT_NEAR(hit.t, 1.0f, 1e-6f);
  (*g)->intersect(make_ray({0.51f, 0, 0}, {0, 0, 1}), hit);
  EXPECT_EQ(hit.geom_id, NIMBUS_NONE);
  // Parallel to the plane: a miss, not a division by zero.
  (*g)->intersect(make_ray({-2, 0, 1}, {1, 0, 0}), hit);
  EXPECT_EQ(hit.geom_id, NIMBUS_NONE);
}

// A triangle hit's frame is the scalar formulas' bit for bit (area lights compute their samples' normals
// with oriented_triangle_normal, and MIS needs the two to agree): ng, oriented towards vertex normals that
// point against the winding; ns, the normalised interpolated normal; dpdu and dpdv from the uvs.
TEST(RayQuery, TriangleFrameIsTheScalarFormulasBitForBit) {
  ShapeDesc s;
  s.type = ShapeType::Mesh;
  MeshData &m = s.mesh;
  m.positions = {{0.3f, -1.1f, 2.0f}, {4.1f, 0.2f, 2.7f}, {0.9f, 3.3f, 1.4f}};
  m.indices = {0, 1, 2};
  m.normals = {normalize(Vec3f{0.1f, 0.2f, -1}), normalize(Vec3f{-0.2f, 0.1f, -1}),
               normalize(Vec3f{0, 0.3f, -1})};
  m.uvs = {{0.1f, 0.2f}, {0.9f, 0.3f}, {0.4f, 0.8f}};
  const SceneDesc d = scene_with({s});
  auto g = GeometryScene::build(d);
  ASSERT_TRUE(g.ok()) << g.error().message;
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.02f, 0.96f);
  for (int i = 0; i < 200; ++i) {
    float b1 = u(rng), b2 = u(rng);
    if (b1 + b2 > 0.98f) b1 = 0.98f - b1, b2 = std::max(0.0f, 0.98f - b2) * 0.5f;
    const Vec3f target = m.positions[0] * (1 - b1 - b2) + m.positions[1] * b1 + m.positions[2] * b2;
    const nimbus_ray_t ray = make_ray(target + Vec3f{0.2f, -0.1f, 3}, Vec3f{-0.2f, 0.1f, -3});
    nimbus_hit_t hit;
    (*g)->intersect(ray, hit);
    ASSERT_EQ(hit.geom_id, 0u);
    nimbus_interaction_t ix;
    (*g)->interaction(ray, hit, ix);
    const float h0 = 1 - hit.u - hit.v;
    const Vec3f ng = oriented_triangle_normal(m, 0, hit.u, hit.v);
    EXPECT_LT(ng.z, 0) << "oriented towards the vertex normals, against the winding";
    const Vec3f ns = normalize(m.normals[0] * h0 + m.normals[1] * hit.u + m.normals[2] * hit.v);
    const Vec3f e1 = m.positions[1] - m.positions[0], e2 = m.positions[2] - m.positions[0];
    const float du1 = m.uvs[1].x - m.uvs[0].x, du2 = m.uvs[2].x - m.uvs[0].x;
    const float dv1 = m.uvs[1].y - m.uvs[0].y, dv2 = m.uvs[2].y - m.uvs[0].y;
    const float det = du1 * dv2 - dv1 * du2;
    const Vec3f dpdu = (e1 * dv2 - e2 * dv1) / det, dpdv = (e2 * du1 - e1 * du2) / det;
    const auto same = [](const Vec3f &want, const float got[3]) {
      return std::memcmp(&want.x, got, 4) == 0 && std::memcmp(&want.y, got + 1, 4) == 0 &&
             std::memcmp(&want.z, got + 2, 4) == 0;
    };
    EXPECT_TRUE(same(ng, ix.ng)) << i;
    EXPECT_TRUE(same(ns, ix.ns)) << i;
    EXPECT_TRUE(same(dpdu, ix.dpdu)) << i;
    EXPECT_TRUE(same(dpdv, ix.dpdv)) << i;
    EXPECT_LT(length(Vec3f::load(ix.p) - target), 1e-5f);
    EXPECT_GT(ix.eps, 0);
  }
}

}  // namespace ray_query_test
}  // namespace nimbus
