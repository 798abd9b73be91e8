// `environment:` — uniform colour, lat-long map, Preetham sky; exactly one form.
#include <gtest/gtest.h>

#include "scene_test_support.hpp"

namespace nimbus::test {
namespace scene_environment_test {

TEST(SceneEnvironment, NoneByDefault) {
  EXPECT_EQ(parse_ok("render: { seed: 1 }\n").environment.type, EnvironmentType::None);
  EXPECT_EQ(parse_ok("environment:\n").environment.type, EnvironmentType::None);
}

TEST(SceneEnvironment, UniformColor) {
  const EnvironmentDesc env =
      parse_ok("environment: { color: [0.1, 0.2, 0.3], scale: 2, group: fill }\n").environment;
  EXPECT_EQ(env.type, EnvironmentType::Color);
  expect_vec(env.color, {0.1f, 0.2f, 0.3f});
  EXPECT_FLOAT_EQ(env.scale, 2);
  EXPECT_EQ(env.group, "fill");
  EXPECT_EQ(env.where.line, 1);
  // The explicit spelling, and a grey.
  expect_vec(parse_ok("environment: { type: color, color: 0.5 }\n").environment.color, Vec3f(0.5f));
}

TEST(SceneEnvironment, MapRelativeToTheSceneFile) {
  TempDir dir;
  const std::string map = dir.write("maps/sky.hdr", "not read while parsing");
  const std::string scene =
      dir.write("scene.yaml", "environment: { map: maps/sky.hdr, scale: 0.5, rotate: 90 }\n");
  const Expected<SceneDesc> parsed = parse_scene_file(scene);
  ASSERT_TRUE(parsed.ok()) << parsed.error().message;
  const EnvironmentDesc &env = parsed->environment;
  EXPECT_EQ(env.type, EnvironmentType::Map);
  EXPECT_EQ(env.map, map);  // absolute
  EXPECT_FLOAT_EQ(env.scale, 0.5f);
  EXPECT_FLOAT_EQ(env.rotate_degrees, 90);
}

TEST(SceneEnvironment, SkyTakesItsSunFromTheSunLight) {
  const SceneDesc scene = parse_ok(R"(environment: { type: sky, turbidity: 4.5, scale: 0.02 }
lights:
  - { type: sun, direction: [0.3, 0.2, -1] }
)");
  const EnvironmentDesc &env = scene.environment;
  EXPECT_EQ(env.type, EnvironmentType::Sky);
  EXPECT_FLOAT_EQ(env.turbidity, 4.5f);
  EXPECT_FLOAT_EQ(env.scale, 0.02f);
  // Towards the sun: against the direction its light travels.
  expect_vec(env.sun_direction, -normalize(Vec3f{0.3f, 0.2f, -1}));
}

TEST(SceneEnvironment, SkyWithoutSunLightNeedsSunDirection) {
  const EnvironmentDesc env = parse_ok("environment: { type: sky, sun_direction: [0, 1, 1] }\n").environment;
  expect_vec(env.sun_direction, normalize(Vec3f{0, 1, 1}));
  EXPECT_FLOAT_EQ(env.turbidity, 3);  // default
}

TEST(SceneEnvironmentErrors, MissingMapFileNamesThePath) {
  TempDir dir;
  const std::string scene = dir.write("scene.yaml", "environment:\n  map: maps/missing.exr\n");
  EXPECT_TRUE(
      error_is(parse_scene_file(scene), scene, 2, 8, "environment.map",
               "environment map '" + (dir.path() / "maps/missing.exr").string() + "' does not exist"));
  std::filesystem::create_directories(dir.path() / "maps/dir.exr");
  EXPECT_TRUE(fails_at("environment: { map: " + (dir.path() / "maps/dir.exr").string() + " }\n", 1, 21,
                       "environment.map", "is a directory"));
}

TEST(SceneEnvironmentErrors, ExactlyOneForm) {
  EXPECT_TRUE(fails_at("environment: { color: 1, map: sky.exr }\n", 1, 26, "environment.map",
                       "cannot be combined with 'color'"));
  EXPECT_TRUE(fails_at("environment: { scale: 2 }\n", 1, 14, "environment",
                       "expected { color: [r, g, b] }, { map: FILE } or { type: sky }"));
  EXPECT_TRUE(fails_at("environment: { type: sky, color: 1, sun_direction: [0, 0, 1] }\n", 1, 27,
                       "environment.color", "cannot be combined with type sky"));
  EXPECT_TRUE(
      fails_at("environment: { type: color }\n", 1, 14, "environment.color", "missing required key 'color'"));
  EXPECT_TRUE(fails_at("environment: { type: hdri }\n", 1, 22, "environment.type",
                       "unknown environment type 'hdri'; known: color, map, sky"));
}

TEST(SceneEnvironmentErrors, KeysOfAnotherForm) {
  EXPECT_TRUE(fails_at("environment: { color: 1, rotate: 90 }\n", 1, 26, "environment.rotate",
                       "unknown key 'rotate' for a uniform environment; allowed: type, color, scale, group"));
  EXPECT_TRUE(fails_at("environment: { type: sky, sun_direction: [0, 0, 1], rotate: 90 }\n", 1, 53,
                       "environment.rotate", "unknown key 'rotate' for a sky"));
}

TEST(SceneEnvironmentErrors, TurbidityAndScaleRanges) {
  EXPECT_TRUE(fails_at("environment: { type: sky, sun_direction: [0, 0, 1], turbidity: 1.5 }\n", 1, 64,
                       "environment.turbidity", "must be in [1.7, 10] (got 1.5)"));
  EXPECT_TRUE(fails_at("environment: { color: 1, scale: -1 }\n", 1, 33, "environment.scale",
                       "must be >= 0 (got -1)"));
}

TEST(SceneEnvironmentErrors, SkySun) {
  EXPECT_TRUE(fails_at("environment: { type: sky }\n", 1, 14, "environment.sun_direction",
                       "missing required key 'sun_direction'"));
  EXPECT_TRUE(fails_at("environment: { type: sky, sun_direction: [0, 0, 0] }\n", 1, 42,
                       "environment.sun_direction", "must not be the zero vector"));
  EXPECT_TRUE(
      fails_at("lights:\n  - { type: sun, direction: [0, 0, -1] }\n"
               "environment: { type: sky, sun_direction: [0, 1, 1] }\n",
               3, 27, "environment.sun_direction",
               "cannot be combined with the sun light at test.yaml:2:5, which sets the sky's sun"));
  EXPECT_TRUE(
      fails_at("lights:\n  - { type: sun, direction: [0, 0, -1] }\n  - { type: sun, direction: [0, 1, -1] }\n"
               "environment: { type: sky }\n",
               4, 14, "environment", "there are 2 (at test.yaml:2:5 and test.yaml:3:5)"));
}

}  // namespace scene_environment_test
}  // namespace nimbus::test
