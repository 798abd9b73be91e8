// The scene service's sharp_bounds (SDK 1.3): which objects can form caustics, and their bounds, as a
// plugin sees them. Glass, mirrors and smooth metals count; diffuse surfaces and metals rougher than the
// threshold do not; a roughness texture counts as possibly smooth; every vertex lies inside both the box
// and the sphere; the count is returned whatever the capacity.
#include <gtest/gtest.h>

#include "query_world.hpp"

namespace nimbus {
namespace sharp_bounds_test {

const char *kScene = R"(
camera: { position: [0, -5, 1], look_at: [0, 0, 0.5] }
materials:
  floor:  { type: diffuse, albedo: [0.5, 0.5, 0.5] }
  glass:  { type: dielectric, ior: 1.5 }
  mirror: { type: conductor, reflectance: [0.9, 0.9, 0.9] }
  satin:  { type: conductor, metal: gold, roughness: 0.5 }
  gloss:  { type: conductor, metal: silver, roughness: 0.2 }
objects:
  - { shape: rectangle, size: [10, 10], material: floor }
  - { shape: sphere, center: [1, 2, 0.5], radius: 0.5, material: glass }
  - { shape: box, size: [1, 2, 0.2], material: mirror, transform: { rotate: [0, 0, 30], translate: [-2, 0, 1] } }
  - { shape: sphere, center: [3, 0, 0.3], radius: 0.3, material: satin }
  - { shape: sphere, center: [-3, 0, 0.3], radius: 0.3, material: gloss }
lights:
  - { type: point, position: [0, 0, 4], intensity: [10, 10, 10] }
)";

class SharpBounds : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(w_.query);
    ASSERT_TRUE(NIMBUS_HAS_MEMBER(w_.query, nimbus_host_scene_query_v1_t, sharp_bounds));
  }
  std::vector<nimbus_object_bounds_t> bounds(float alpha_max) const {
    std::vector<nimbus_object_bounds_t> b(w_.query->sharp_bounds(w_.host(), alpha_max, nullptr, 0));
    EXPECT_EQ(w_.query->sharp_bounds(w_.host(), alpha_max, b.data(), uint32_t(b.size())), b.size());
    return b;
  }

  QueryWorld w_{kScene};
};

TEST_F(SharpBounds, GlassMirrorsAndSmoothMetalsOnly) {
  // GGX alpha = roughness^2: the gold sphere has 0.25, the silver one 0.04.
  const std::vector<nimbus_object_bounds_t> b = bounds(0.1f);
  ASSERT_EQ(b.size(), 3u) << "glass, mirror box and the glossy silver sphere";
  EXPECT_FLOAT_EQ(b[0].center[0], 1);
  EXPECT_FLOAT_EQ(b[0].center[1], 2);
  EXPECT_FLOAT_EQ(b[0].radius, 0.5f);
  EXPECT_FLOAT_EQ(b[2].center[0], -3);
  EXPECT_EQ(bounds(0.01f).size(), 2u) << "the silver sphere is not sharp at alpha 0.01";
  EXPECT_EQ(bounds(1.0f).size(), 4u) << "every non-diffuse object below alpha 1";
  // The mirror box: its 8 corners inside the box and the sphere.
  const nimbus_object_bounds_t &m = b[1];
  const MeshData &mesh = w_.desc.shapes[2].mesh;
  ASSERT_FALSE(mesh.positions.empty());
  for (const Vec3f &p : mesh.positions) {
    for (int k = 0; k < 3; ++k) {
      EXPECT_LE(m.lo[k], p[k]);
      EXPECT_GE(m.hi[k], p[k]);
    }
    EXPECT_LE(length(p - Vec3f::load(m.center)), m.radius * 1.0001f);
  }
  EXPECT_LT(m.radius, 1.2f) << "half the box diagonal (half extents 0.5, 1, 0.1: 1.12)";
}

TEST_F(SharpBounds, CountIsReturnedWhateverTheCapacity) {
  nimbus_object_bounds_t one{};
  EXPECT_EQ(w_.query->sharp_bounds(w_.host(), 0.1f, &one, 1), 3u);
  EXPECT_FLOAT_EQ(one.radius, 0.5f);
  EXPECT_EQ(w_.query->sharp_bounds(w_.host(), 0.1f, nullptr, 0), 3u);
}

TEST(SharpBoundsScene, DiffuseSceneHasNone) {
  auto desc = parse_scene_string(R"(
materials: { white: { type: diffuse } }
objects: [ { shape: sphere, radius: 1, material: white } ]
lights: [ { type: point, position: [0, 0, 3], intensity: [1, 1, 1] } ]
)",
                                 "diffuse.yaml");
  ASSERT_TRUE(desc.ok()) << desc.error().message;
  auto world = World::build(desc.value(), desc.value().render.filter);
  ASSERT_TRUE(world.ok());
  EXPECT_TRUE(world.value()->sharp_objects.empty());
}

}  // namespace sharp_bounds_test
}  // namespace nimbus
