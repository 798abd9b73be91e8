// Embree's robust (watertight) triangle test is chosen per scene: only where some object lies far from
// the origin for its size, where the fast test's cracks at shared edges let light through
// (tests/extremes/leak_test.cpp has the renders that leak without it).
#include <gtest/gtest.h>

#include "geometry/geometry_scene.hpp"
#include "scene/scene_desc.hpp"

namespace nimbus {
namespace watertight_test {

ShapeDesc box(const Vec3f &lo, const Vec3f &hi) {
  ShapeDesc s;
  s.type = ShapeType::Mesh;
  for (int i = 0; i < 8; ++i)
    s.mesh.positions.push_back({i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z});
  const uint32_t f[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                            {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (auto &q : f) s.mesh.indices.insert(s.mesh.indices.end(), {q[0], q[1], q[2], q[0], q[2], q[3]});
  return s;
}

bool watertight(std::vector<ShapeDesc> shapes) {
  SceneDesc d;
  d.materials.push_back(MaterialDesc{});
  d.shapes = std::move(shapes);
  auto g = GeometryScene::build(d);
  EXPECT_TRUE(g.ok());
  return g.ok() && (*g)->watertight();
}

TEST(Watertight, ScenesAroundTheOriginUseTheFastTestAtAnyScale) {
  for (float s : {1e-4f, 1.0f, 1e3f, 1e6f}) {
    EXPECT_FALSE(watertight({box(Vec3f(-s), Vec3f(s))})) << s;
    EXPECT_FALSE(watertight({box(Vec3f(0), Vec3f(s)), box(Vec3f(10 * s), Vec3f(12 * s))})) << s;
  }
}

TEST(Watertight, AnObjectFarFromTheOriginForItsSizeGetsTheRobustTest) {
  for (float s : {1e-4f, 1.0f, 1e3f}) {
    EXPECT_TRUE(watertight({box(Vec3f(1000 * s), Vec3f(1002 * s))})) << s;
    // One small object far out is enough, whatever else the scene holds.
    EXPECT_TRUE(watertight({box(Vec3f(-s), Vec3f(s)), box(Vec3f(500 * s, 0, 0), Vec3f(501 * s, s, s))})) << s;
  }
  // Around the bound (64 sizes out): 61 units out for a size of 1.01 stays fast, 66 turns robust.
  EXPECT_FALSE(watertight({box(Vec3f(60, 0, 0), Vec3f(61, 0.1f, 0.1f))}));
  EXPECT_TRUE(watertight({box(Vec3f(65, 0, 0), Vec3f(66, 0.1f, 0.1f))}));
}

}  // namespace watertight_test
}  // namespace nimbus
