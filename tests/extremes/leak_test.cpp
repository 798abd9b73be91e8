// Light leaks in full renders: a closed box with every light outside it must be exactly black inside, at
// every scale. Outside there is a two-sided emitter enclosing everything, a bright panel facing one wall
// and a point light above the lid, so a ray that slips through a wall, a corner or an edge, or a shadow
// ray that stops short of the wall between it and the light, finds light. Inside, a glass and a rough
// metal sphere near the walls (0.1 and 0.2 box-units away) offset their rays towards those walls.
//
// The far-from-origin cases fail today: see tests/extremes/README.md (corner hits at t = 0, the 2^-18
// surface epsilon, and spawn_ray_to stopping shadow rays 4 epsilons short of the light).
#include <gtest/gtest.h>

#include <algorithm>

#include "extremes_support.hpp"

namespace nimbus::extremes {
namespace leak_test {

// `s` scales every length (the point light's intensity by s^2, so irradiance stays the same), `ox` moves
// the scene along x, `panel_gap` is the distance from the +x wall to the panel facing it (box units).
std::string sealed_box(double s, double ox, double panel_gap) {
  const auto P = [&](double x, double y, double z) { return vec(ox + s * x, s * y, s * z); };
  const double intensity = 1e4 * s * s;
  return R"(
render: { resolution: [24, 24], seed: 5, max_depth: 10 }
camera: { position: )" +
         P(-0.5, -0.85, -0.6) + ", look_at: " + P(0.6, 0.4, 0.5) + R"(, up: [0, 0, 1], fov: 100 }
materials:
  white: { type: diffuse, albedo: [0.9, 0.9, 0.9] }
  metal: { type: conductor, reflectance: [0.95, 0.95, 0.95], roughness: 0.3 }
  glass: { type: dielectric, ior: 1.5 }
  lamp: { type: diffuse, albedo: [0, 0, 0] }
objects:
  - { shape: box, size: )" +
         vec(2 * s, 2 * s, 2 * s) + ", material: white, transform: { translate: " + P(0, 0, 0) +
         R"( } }
  - { shape: sphere, center: )" +
         P(0.5, 0.5, -0.6) + ", radius: " + num(0.3 * s) + R"(, material: glass }
  - { shape: sphere, center: )" +
         P(-0.5, 0.4, 0.5) + ", radius: " + num(0.3 * s) + R"(, material: metal }
  - { shape: sphere, center: )" +
         P(0, 0, 0) + ", radius: " + num(10 * s) +
         R"(, material: lamp, two_sided: true, emission: { radiance: [50, 50, 50] } }
  - { shape: rectangle, size: )" +
         "[" + num(1.8 * s) + ", " + num(1.8 * s) + "]" +
         R"(, material: lamp, emission: { radiance: [1000, 1000, 1000] },
      transform: { rotate: [0, -90, 0], translate: )" +
         P(1 + panel_gap, 0, 0) + R"( } }
lights:
  - { type: point, position: )" +
         P(0, 0, 1.2) + ", intensity: " + vec(intensity, intensity, intensity) + R"( }
)";
}

void expect_black(const Rendered &img, const std::string &what) {
  ASSERT_TRUE(img.ok);
  EXPECT_EQ(img.nonfinite, 0u) << what;
  size_t lit = 0;
  for (size_t i = 0; i < img.rgb.size(); i += 3)
    lit += img.rgb[i] != 0 || img.rgb[i + 1] != 0 || img.rgb[i + 2] != 0;
  EXPECT_EQ(lit, 0u) << what << ": light leaked into " << lit << " of " << img.width * img.height
                     << " pixels (brightest value " << *std::max_element(img.rgb.begin(), img.rgb.end())
                     << ")";
}

class Leak : public ::testing::TestWithParam<double> {};

// The panel is 1e-4 box-units from the wall: about 800 float ulps at any scale about the origin.
TEST_P(Leak, SealedBoxIsBlackInside) {
  SceneRenderer r;
  const double s = GetParam();
  expect_black(render(r, sealed_box(s, 0, 1e-4), pt(32, 3)), "scale " + num(s));
}

INSTANTIATE_TEST_SUITE_P(Extremes, Leak, ::testing::Values(1e-4, 1.0, 1e3, 1e6), [](const auto &info) {
  return std::string(info.index == 0 ? "s1em4" : info.index == 1 ? "s1" : info.index == 2 ? "s1e3" : "s1e6");
});

// Far from the origin a float keeps only 16 (at 1e3) to 7 (at 1e5) fraction bits; every gap in the scene
// is still at least 13 ulps there (the panel is 0.5 units off, the spheres 0.1 and 0.2, the point light
// 0.2 above the lid), which robust offsetting must resolve.
// Found F1/F2 (tests/extremes/README.md).
TEST(Leak, SealedBoxFarFromOriginIsBlackInside) {
  SceneRenderer r;
  for (double offset : {1e3, 1e5})
    expect_black(render(r, sealed_box(1, offset, 0.5), pt(32, 3)), "offset " + num(offset));
}

// The smallest repro of one far-from-origin leak: an empty closed box and one point light 0.2 above its
// lid. Shadow rays from inside must stop at the lid; they once ended 4 * 2^-18 of the light's coordinates
// before it - 0.46 units at 3e4 - short of the lid, and the light shone in (F3 in README.md).
TEST(Leak, PointLightAboveTheLidFarFromOrigin) {
  SceneRenderer r;
  for (double offset : {1e4, 3e4, 1e5}) {
    const std::string o = num(offset);
    const std::string scene = R"(
render: { resolution: [16, 16], seed: 5, max_depth: 4 }
camera: { position: [)" + o + R"(, -0.8, -0.5], look_at: [)" +
                              o + R"(, 1, 0], up: [0, 0, 1], fov: 90 }
materials: { white: { type: diffuse, albedo: [0.9, 0.9, 0.9] } }
objects:
  - { shape: box, size: [2, 2, 2], material: white, transform: { translate: [)" +
                              o + R"(, 0, 0] } }
lights:
  - { type: point, position: [)" +
                              o + R"(, 0, 1.2], intensity: [1e4, 1e4, 1e4] }
)";
    expect_black(render(r, scene, pt(8, 3)), "offset " + o);
  }
}

}  // namespace leak_test
}  // namespace nimbus::extremes
