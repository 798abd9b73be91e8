// The albedo element: the first non-specular surface's albedo, computed only when asked for, with the
// same beauty either way (the host call consumes no random numbers).
#include <gtest/gtest.h>

#include "support/render_support.hpp"

namespace nimbus::testing {
namespace albedo_element_test {

const char *kBox = R"(
render: { resolution: [32, 32], seed: 3, max_depth: 6 }
camera: { position: [0, -3.9, 1], look_at: [0, 0, 1], up: [0, 0, 1], fov: 39 }
materials:
  white: { type: diffuse, albedo: [0.75, 0.75, 0.75] }
  red:   { type: diffuse, albedo: [0.63, 0.065, 0.05] }
  glass: { type: dielectric, ior: 1.5 }
  lamp:  { type: diffuse, albedo: [0, 0, 0] }
objects:
  - { shape: rectangle, size: [2, 2], material: white }
  - { shape: rectangle, size: [2, 2], material: white, transform: { rotate: [90, 0, 0], translate: [0, 1, 1] } }
  - { shape: rectangle, size: [2, 2], material: red, transform: { rotate: [0, 90, 0], translate: [-1, 0, 1] } }
  - { shape: sphere, center: [0.3, 0, 0.4], radius: 0.4, material: glass }
  - { shape: rectangle, size: [0.6, 0.6], material: lamp, emission: { radiance: [17, 15, 12] },
      transform: { rotate: [180, 0, 0], translate: [0, 0, 1.99] } }
)";

class AlbedoElement : public ::testing::TestWithParam<const char *> {};

TEST_P(AlbedoElement, IsTheFirstRoughSurfacesAlbedoAndLeavesBeautyAlone) {
  SceneRenderer r;
  RenderRequest req;
  req.integrator = GetParam(), req.iterations = 4, req.seed = 5;
  const auto plain = r.render(kBox, req);
  req.elements = {"albedo"};
  const auto with = r.render(kBox, req);
  ASSERT_EQ(plain.layers.count("albedo"), 0u);
  ASSERT_EQ(with.layers.count("albedo"), 1u);
  EXPECT_EQ(plain.layers.at("beauty").data, with.layers.at("beauty").data);

  const std::vector<float> &a = with.layers.at("albedo").data;
  ASSERT_EQ(a.size(), size_t(32 * 32 * 3));
  // The image centre sees the back wall only (seen through nothing specular): exactly its albedo.
  for (const uint32_t y : {15u, 16u})
    for (const uint32_t x : {15u, 16u})
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[(y * 32 + x) * 3 + c], 0.75f, 1e-5f) << x << "," << y;
  // The red wall shows as red somewhere on the left.
  bool red = false;
  for (size_t p = 0; p < a.size(); p += 3) red = red || (a[p] > 0.5f && a[p + 1] < 0.1f);
  EXPECT_TRUE(red);
}

INSTANTIATE_TEST_SUITE_P(Integrators, AlbedoElement, ::testing::Values("nimbus.pt", "nimbus.caustics"));

}  // namespace albedo_element_test
}  // namespace nimbus::testing
