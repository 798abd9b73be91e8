// Grazing incidence: a camera looking along a large plane (its rays meet the plane at angles down to
// zero, or run exactly inside it), lights just above the plane and an area light seen edge-on. The BSDFs
// and light pdfs see cosines near 0 everywhere: no NaN or Inf may reach the film, and in a furnace the
// grazing view still conserves energy.
#include <gtest/gtest.h>

#include <algorithm>
#include <ostream>
#include <string>

#include "extremes_support.hpp"
#include "furnace_support.hpp"

namespace nimbus::extremes {
namespace grazing_test {

struct GrazingCase {
  const char *name;
  const char *material;  // YAML of the plane's material
  double camera_height;  // 0: the camera lies in the plane
};

// A 2 km plane, the camera `h` above it looking along it; a sphere resting on it, a point light 1 cm
// above it, a panel standing on it lit edge-on by the camera's view direction and a panel tilted to
// within 0.5 degrees of the plane.
std::string grazing_scene(const GrazingCase &g) {
  const double h = g.camera_height;
  return R"(
render: { resolution: [32, 32], seed: 9, max_depth: 8 }
camera: { position: )" +
         vec(0, -900, h) + ", look_at: " + vec(0, 900, h) + R"(, up: [0, 0, 1], fov: 30 }
materials:
  plane: )" +
         g.material + R"(
  white: { type: diffuse, albedo: [0.8, 0.8, 0.8] }
  lamp: { type: diffuse, albedo: [0, 0, 0] }
objects:
  - { shape: rectangle, size: [2000, 2000], material: plane }
  - { shape: sphere, center: [3, 0, 2], radius: 2, material: plane }
  - { shape: rectangle, size: [40, 4], material: lamp, emission: { radiance: [30, 30, 30] },
      transform: { rotate: [90, 0, 0], translate: [0, 400, 2] } }
  - { shape: rectangle, size: [100, 100], material: lamp, two_sided: true, emission: { radiance: [5, 5, 5] },
      transform: { rotate: [0.5, 0, 0], translate: [-60, 200, 0.5] } }
  - { shape: box, size: [10, 0.001, 10], material: white, transform: { translate: [20, 100, 5] } }
lights:
  - { type: point, position: [0, 100, 0.01], intensity: [1e4, 1e4, 1e4] }
  - { type: point, position: [-30, -800, 0.0001], intensity: [100, 100, 100] }
)";
}

void PrintTo(const GrazingCase &g, std::ostream *os) { *os << g.name; }

class Grazing : public ::testing::TestWithParam<GrazingCase> {};

TEST_P(Grazing, NoNonFiniteSamples) {
  SceneRenderer r;
  const Rendered img = render(r, grazing_scene(GetParam()), pt(16, 41));
  ASSERT_TRUE(img.ok);
  EXPECT_EQ(img.nonfinite, 0u) << GetParam().name;
  EXPECT_GT(channel_mean(img, 0).mean, 0) << "the plane should be lit";
}

const char *const kWhite = "{ type: diffuse, albedo: [0.8, 0.8, 0.8] }";
const char *const kRoughGold = "{ type: conductor, metal: gold, roughness: 0.3 }";
const char *const kSmoothGold = "{ type: conductor, metal: gold, roughness: 0 }";
const char *const kRoughGlass = "{ type: dielectric, ior: 1.5, roughness: 0.3 }";
const char *const kSmoothGlass = "{ type: dielectric, ior: 2.4, roughness: 0 }";

INSTANTIATE_TEST_SUITE_P(Extremes, Grazing,
                         ::testing::Values(GrazingCase{"white_1mm", kWhite, 1e-3},
                                           GrazingCase{"white_inplane", kWhite, 0},
                                           GrazingCase{"roughgold_1mm", kRoughGold, 1e-3},
                                           GrazingCase{"roughgold_inplane", kRoughGold, 0},
                                           GrazingCase{"smoothgold_1mm", kSmoothGold, 1e-3},
                                           GrazingCase{"roughglass_1mm", kRoughGlass, 1e-3},
                                           GrazingCase{"roughglass_inplane", kRoughGlass, 0},
                                           GrazingCase{"smoothglass_1mm", kSmoothGlass, 1e-3}),
                         [](const auto &info) { return std::string(info.param.name); });

// A sun 0.01 degrees above the horizon (disk and delta) and a spot light 1 mm above the plane aiming along
// it: incident cosines of 1e-4 and less on the plane, and a sun disk that the plane half hides.
TEST(GrazingDistantLights, SunAndSpotAtTheHorizon) {
  for (const char *sun : {"angular_diameter: 0.53", "angular_diameter: 0"}) {
    const std::string scene = R"(
render: { resolution: [32, 32], seed: 9, max_depth: 6 }
camera: { position: [0, -900, 0.001], look_at: [0, 900, 0.001], up: [0, 0, 1], fov: 30 }
materials:
  white: { type: diffuse, albedo: [0.8, 0.8, 0.8] }
  gold: { type: conductor, metal: gold, roughness: 0.3 }
  glass: { type: dielectric, ior: 1.5, roughness: 0.2 }
objects:
  - { shape: rectangle, size: [2000, 2000], material: white }
  - { shape: sphere, center: [3, 0, 2], radius: 2, material: gold }
  - { shape: sphere, center: [-6, 50, 2], radius: 2, material: glass }
lights:
  - { type: sun, direction: [0, -1, -0.00017], irradiance: [5, 5, 5], )" +
                              std::string(sun) + R"( }
  - { type: spot, position: [0, 100, 0.001], direction: [0, -1, 0], cone: 20, softness: 5,
      intensity: [1e4, 1e4, 1e4] }
)";
    SCOPED_TRACE(sun);
    NIMBUS_ASSERT_PARSES(scene, "sun and spot lights");
    SceneRenderer r;
    const Rendered img = render(r, scene, pt(16, 49));
    ASSERT_TRUE(img.ok);
    EXPECT_EQ(img.nonfinite, 0u);
    EXPECT_GT(channel_mean(img, 0).mean, 0) << "the plane should be lit";
  }
}

// The same grazing view of a plane inside a uniform emitter: a white Lambertian plane and an ideal mirror
// are lossless (every pixel 1), a rough mirror may only lose.
std::string grazing_furnace(const char *material) {
  return R"(
render: { resolution: [24, 24], seed: 2, max_depth: 64 }
camera: { position: [0, -50, 0.001], look_at: [0, 50, 0.001], up: [0, 0, 1], fov: 20 }
materials:
  plane: )" +
         std::string(material) + R"(
  lamp: { type: diffuse, albedo: [0, 0, 0] }
objects:
  - { shape: rectangle, size: [400, 400], material: plane }
  - { shape: sphere, center: [0, 0, 0], radius: 1000, material: lamp, two_sided: true,
      emission: { radiance: [1, 1, 1] } }
)";
}

TEST(GrazingFurnace, WhitePlaneIsOne) {
  SceneRenderer r;
  const Rendered img = render(r, grazing_furnace("{ type: diffuse, albedo: [1, 1, 1] }"), pt(32, 43));
  ASSERT_TRUE(img.ok);
  EXPECT_EQ(img.nonfinite, 0u);
  expect_furnace_level(img, 1.0, 0.01);
}

TEST(GrazingFurnace, IdealMirrorPlaneIsExactlyOne) {
  SceneRenderer r;
  const Rendered img =
      render(r, grazing_furnace("{ type: conductor, reflectance: [1, 1, 1], roughness: 0 }"), pt(4, 45));
  ASSERT_TRUE(img.ok);
  EXPECT_EQ(img.nonfinite, 0u);
  float worst = 0;
  for (float v : img.rgb) worst = std::max(worst, std::abs(v - 1));
  EXPECT_LE(worst, 1e-5f);
}

TEST(GrazingFurnace, RoughMirrorPlaneNeverGains) {
  SceneRenderer r;
  for (const char *m : {"{ type: conductor, reflectance: [1, 1, 1], roughness: 0.5 }",
                        "{ type: conductor, reflectance: [1, 1, 1], roughness: 1 }",
                        "{ type: dielectric, ior: 1.33, roughness: 1 }"}) {
    SCOPED_TRACE(m);
    const Rendered img = render(r, grazing_furnace(m), pt(32, 47));
    ASSERT_TRUE(img.ok);
    EXPECT_EQ(img.nonfinite, 0u);
    expect_furnace_bounded(img, 0.0);
  }
}

}  // namespace grazing_test
}  // namespace nimbus::extremes
