// `lights:` — point, spot and sun lights, intensity or power, groups.
#include <gtest/gtest.h>

#include <cmath>

#include "lights/light.hpp"
#include "scene_test_support.hpp"

namespace nimbus::test {
namespace scene_lights_test {

// By value: callers pass the temporary scene of parse_ok.
LightDesc only_light(const SceneDesc &scene) {
  EXPECT_EQ(scene.lights.size(), 1u);
  return scene.lights.empty() ? LightDesc{} : scene.lights[0];
}

TEST(SceneLights, PointIntensityOrPower) {
  const SceneDesc scene = parse_ok(R"(lights:
  - { type: point, position: [1, 2, 3], intensity: [1, 2, 3], group: key }
  - { type: point, position: [0, 0, 1], power: 100 }
  - { type: point, position: [0, 0, 1], power: [12.566370614359172, 0, 25.132741228718345] }
)");
  ASSERT_EQ(scene.lights.size(), 3u);
  EXPECT_EQ(scene.lights[0].type, LightType::Point);
  expect_vec(scene.lights[0].position, {1, 2, 3});
  expect_vec(scene.lights[0].intensity, {1, 2, 3});
  EXPECT_EQ(scene.lights[0].group, "key");
  // A point light radiates its power uniformly over 4 pi steradians.
  expect_vec(scene.lights[1].intensity, Vec3f(100 / (4 * kPi)), 1e-4f);
  expect_vec(scene.lights[2].intensity, {1, 0, 2});
  EXPECT_EQ(scene.lights[1].group, "");
  EXPECT_EQ(scene.lights[1].where.line, 3);
}

TEST(SceneLights, Spot) {
  const LightDesc l = only_light(parse_ok(
      "lights:\n  - { type: spot, position: [0, -2, 5], direction: [0, 0, -2], cone: 30, softness: 10, "
      "intensity: 50, group: stage }\n"));
  EXPECT_EQ(l.type, LightType::Spot);
  expect_vec(l.position, {0, -2, 5});
  expect_vec(l.direction, {0, 0, -1});  // normalised
  EXPECT_FLOAT_EQ(l.cone_degrees, 30);
  EXPECT_FLOAT_EQ(l.softness_degrees, 10);
  expect_vec(l.intensity, Vec3f(50));
  EXPECT_EQ(l.group, "stage");
}

TEST(SceneLights, SpotDefaults) {
  const LightDesc l =
      only_light(parse_ok("lights: [{ type: spot, position: [0, 0, 1], direction: [1, 0, 0] }]\n"));
  EXPECT_FLOAT_EQ(l.cone_degrees, 30);
  EXPECT_FLOAT_EQ(l.softness_degrees, 5);
  expect_vec(l.intensity, Vec3f(1));
  // A cone narrower than the default softness narrows the softness rather than failing on an unwritten key.
  const LightDesc narrow =
      only_light(parse_ok("lights: [{ type: spot, position: [0, 0, 1], direction: [1, 0, 0], cone: 3 }]\n"));
  EXPECT_FLOAT_EQ(narrow.softness_degrees, 3);
}

// `power:` must make the spot emit exactly that many watts with the host's own fall-off profile.
TEST(SceneLights, SpotPowerIsTheIntegralOfItsFalloff) {
  for (const auto &[cone, softness] :
       std::vector<std::pair<float, float>>{{30, 10}, {60, 0}, {5, 5}, {180, 40}}) {
    const LightDesc l = only_light(
        parse_ok("lights: [{ type: spot, position: [0, 0, 0], direction: [0, 0, 1], "
                 "cone: " +
                 std::to_string(cone) + ", softness: " + std::to_string(softness) + ", power: 100 }]\n"));
    SpotLight spot;
    spot.cos_falloff_end = std::cos(radians(cone));
    spot.cos_falloff_start = std::cos(radians(cone - softness));
    // Power = I * integral of falloff over the sphere = I * 2 pi * integral over cos(theta) in [-1, 1].
    const int n = 200000;
    double integral = 0;
    for (int i = 0; i < n; ++i) integral += spot.falloff(float(-1 + 2 * (i + 0.5) / n));
    integral *= 2.0 / n * 2 * kPi;
    EXPECT_NEAR(l.intensity.x * integral, 100, 0.05) << "cone " << cone << " softness " << softness;
    // The formula the documentation states.
    const double inner = radians(cone - softness), outer = radians(cone);
    EXPECT_NEAR(l.intensity.x, 100 / (2 * kPi * (1 - (std::cos(inner) + std::cos(outer)) / 2)),
                1e-3 * l.intensity.x);
  }
}

TEST(SceneLights, Sun) {
  const SceneDesc scene = parse_ok(R"(lights:
  - { type: sun, direction: [-1, 1, -2], irradiance: [3, 2, 1], angular_diameter: 0.6, group: sun }
  - { type: sun, direction: [0, 0, -1], angular_diameter: 0 }
)");
  ASSERT_EQ(scene.lights.size(), 2u);
  const LightDesc &s = scene.lights[0];
  EXPECT_EQ(s.type, LightType::Sun);
  expect_vec(s.direction, normalize(Vec3f{-1, 1, -2}));
  expect_vec(s.irradiance, {3, 2, 1});
  EXPECT_FLOAT_EQ(s.angular_diameter_degrees, 0.6f);
  EXPECT_EQ(s.group, "sun");
  // Defaults: 1 W/m^2 and the real sun's 0.53 degrees; 0 is a delta direction.
  expect_vec(scene.lights[1].irradiance, Vec3f(1));
  EXPECT_FLOAT_EQ(scene.lights[1].angular_diameter_degrees, 0);
  EXPECT_FLOAT_EQ(
      parse_ok("lights: [{ type: sun, direction: [0, 0, -1] }]\n").lights.at(0).angular_diameter_degrees,
      0.53f);
}

TEST(SceneLightErrors, IntensityAndPowerTogether) {
  EXPECT_TRUE(fails_at("lights:\n  - { type: point, position: [0, 0, 1], intensity: 1, power: 10 }\n", 2, 55,
                       "lights[0].power", "cannot be combined with 'intensity'"));
}

TEST(SceneLightErrors, NegativePower) {
  EXPECT_TRUE(fails_at("lights:\n  - { type: point, position: [0, 0, 1], power: -5 }\n", 2, 48,
                       "lights[0].power", "must be >= 0 (got -5)"));
}

TEST(SceneLightErrors, SpotNeedsADirection) {
  EXPECT_TRUE(fails_at("lights:\n  - { type: spot, position: [0, 0, 1] }\n", 2, 5, "lights[0].direction",
                       "missing required key 'direction'"));
}

TEST(SceneLightErrors, ZeroDirection) {
  EXPECT_TRUE(fails_at("lights:\n  - { type: sun, direction: [0, 0, 0] }\n", 2, 29, "lights[0].direction",
                       "must not be the zero vector"));
}

TEST(SceneLightErrors, ConeOutOfRange) {
  const std::string spot = "lights:\n  - { type: spot, position: [0, 0, 1], direction: [0, 0, -1], cone: ";
  EXPECT_TRUE(fails_at(spot + "0 }\n", 2, 69, "lights[0].cone", "must be in (0, 180] (got 0)"));
  EXPECT_TRUE(fails_at(spot + "181 }\n", 2, 69, "lights[0].cone", "must be in (0, 180] (got 181)"));
  EXPECT_TRUE(
      fails_at(spot + "20, softness: 25 }\n", 2, 83, "lights[0].softness", "must be in [0, 20] (got 25)"));
}

TEST(SceneLightErrors, SunKeys) {
  EXPECT_TRUE(fails_at("lights:\n  - { type: sun, direction: [0, 0, -1], position: [0, 0, 9] }\n", 2, 41,
                       "lights[0].position", "unknown key 'position' for a sun light"));
  EXPECT_TRUE(fails_at("lights:\n  - { type: sun, direction: [0, 0, -1], angular_diameter: -1 }\n", 2, 59,
                       "lights[0].angular_diameter", "must be in [0, 180] (got -1)"));
  EXPECT_TRUE(fails_at("lights:\n  - { type: sun, direction: [0, 0, -1], power: 3 }\n", 2, 41,
                       "lights[0].power", "unknown key 'power' for a sun light"));
}

}  // namespace scene_lights_test
}  // namespace nimbus::test
