// `camera.shutter:` and objects' `motion:` keys: what they parse into, and each mistake named at its
// line and column (keys out of order, times outside the shutter, half turns, stretched spheres).
#include <gtest/gtest.h>

#include "scene_test_support.hpp"

namespace nimbus::test {
namespace scene_motion_test {

// Lines 1-3: a shutter over [0, 1], the material; `objects:` is line 4 and the object starts at 5:5.
const std::string kHead =
    "camera: { shutter: { open: 0, close: 1 } }\nmaterials:\n  white: { type: diffuse }\n";

TEST(SceneMotion, ShutterAndKeysParseIntoAMovingShape) {
  const SceneDesc scene = parse_ok(
      "camera: { shutter: { open: 1, close: 3, curve: [[0, 0], [0.5, 1], [1, 0]] } }\n"
      "materials: { white: { type: diffuse } }\n"
      "objects:\n"
      "  - shape: box\n    size: [1, 1, 1]\n    material: white\n"
      "    motion: [{ time: 1, translate: [0, 0, 0] }, { time: 3, translate: [4, 0, 0], rotate: [0, 0, 90] "
      "}]\n"
      "  - { shape: sphere, radius: 0.5, material: white, motion: [{ time: 2, translate: [0, 1, 0], scale: 2 "
      "}] }\n");
  const Shutter &s = scene.camera.shutter;
  EXPECT_EQ(s.open(), 1.0f);
  EXPECT_EQ(s.close(), 3.0f);
  EXPECT_NEAR(s.pdf(2.0f), 1.0f, 1e-6f) << "a triangle of height 1 over 2 time units";
  ASSERT_EQ(scene.shapes.size(), 2u);
  const ShapeDesc &box = scene.shapes[0];
  ASSERT_TRUE(box.motion);
  EXPECT_TRUE(box.motion->moves());
  // The mesh stays in object space; the motion places it.
  for (const Vec3f &p : box.mesh.positions) EXPECT_NEAR(std::abs(p.x), 0.5f, 1e-6f);
  EXPECT_NEAR(box.motion->at(2.0f).point({0, 0, 0}).x, 2.0f, 1e-5f);
  const ShapeDesc &ball = scene.shapes[1];
  ASSERT_TRUE(ball.motion);
  EXPECT_FALSE(ball.motion->moves()) << "one key holds still";
  EXPECT_EQ(ball.radius, 0.5f);
  EXPECT_NEAR(ball.motion->at(1.0f).point({1, 0, 0}).x, 2.0f, 1e-5f);
}

TEST(SceneMotion, ShutterMistakes) {
  EXPECT_TRUE(fails_at("camera: { shutter: { open: 2, close: 1 } }\n", 1, 38, "camera.shutter.close",
                       "the shutter closes (1) before it opens (2)"));
  EXPECT_TRUE(fails_at("camera: { shutter: { close: 1, curve: [[0.2, 1], [1, 1]] } }\n", 1, 41,
                       "camera.shutter.curve[0][0]", "the curve must start at x = 0"));
  EXPECT_TRUE(fails_at("camera: { shutter: { close: 1, curve: [[0, 1], [0.5, 1]] } }\n", 1, 39,
                       "camera.shutter.curve", "the curve must run from x = 0 to x = 1"));
  EXPECT_TRUE(fails_at("camera: { shutter: { close: 1, curve: [[0, 0], [1, 0]] } }\n", 1, 39,
                       "camera.shutter.curve", "exposes nothing"));
}

TEST(SceneMotion, KeyMistakesAreNamedWhereTheyAre) {
  const std::string object = "objects:\n  - shape: box\n    size: [1, 1, 1]\n    material: white\n";
  EXPECT_TRUE(fails_at(kHead + object + "    motion: [{ time: 0.5 }, { time: 0.2 }]\n", 8, 37,
                       "objects[0].motion[1].time", "keys out of order: time 0.2 follows 0.5"));
  EXPECT_TRUE(fails_at(kHead + object + "    motion: [{ time: 0 }, { time: 2 }]\n", 8, 35,
                       "objects[0].motion[1].time",
                       "time 2 lies outside the shutter [0, 1] (camera.shutter)"));
  EXPECT_TRUE(fails_at(kHead + object + "    motion: [{ time: 0 }, { time: 1, rotate: [0, 0, 180] }]\n", 8,
                       27, "objects[0].motion[1]", "half a turn"));
  EXPECT_TRUE(fails_at(kHead + object + "    transform: { scale: 2 }\n    motion: [{ time: 0 }]\n", 8, 5,
                       "objects[0].transform", "cannot be combined with 'motion'"));
  // Without a shutter, keys at two times cannot both lie in it.
  EXPECT_TRUE(fails_at(
      "materials:\n  white: { type: diffuse }\n" + object + "    motion: [{ time: 0 }, { time: 1 }]\n", 7, 35,
      "objects[0].motion[1].time", "outside the shutter [0, 0]"));
  // Spheres stay spheres at every key.
  EXPECT_TRUE(fails_at(kHead + "objects:\n  - shape: sphere\n    radius: 1\n    material: white\n"
                               "    motion: [{ time: 0 }, { time: 1, scale: [1, 2, 1] }]\n",
                       8, 27, "objects[0].motion[1]", "allows only rotation, translation and uniform scale"));
}

TEST(SceneMotion, DeformationStepsAndTheirMistakes) {
  const std::string tri =
      "  - { shape: mesh, material: white, positions: [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "
      "indices: [0, 1, 2], ";
  const SceneDesc scene =
      parse_ok(kHead + "objects:\n" + tri +
               "deform: [[[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 0, 1], [1, 0, 1], [0, 1, 1]]],"
               " transform: { translate: [5, 0, 0] } }\n");
  const MeshData &m = scene.shapes.at(0).mesh;
  ASSERT_TRUE(m.deforms());
  EXPECT_EQ(m.position_steps.size(), 2u);
  EXPECT_NEAR(m.position_steps[1][2].x, 5.0f, 1e-6f) << "the transform moves every step";
  EXPECT_NEAR(m.position_steps[1][2].z, 1.0f, 1e-6f);
  EXPECT_EQ(m.steps_open, 0.0f);
  EXPECT_EQ(m.steps_close, 1.0f);
  EXPECT_TRUE(
      fails_at(kHead + "objects:\n" + tri + "deform: [[[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 0, 1]]] }\n", 5,
               147, "objects[0].deform[1]", "has 1 vertices but the mesh has 3"));
  EXPECT_TRUE(
      fails_at("materials:\n  white: { type: diffuse }\nobjects:\n" + tri +
                   "deform: [[[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 0, 1], [1, 0, 1], [0, 1, 1]]] }\n",
               4, 111, "objects[0].deform", "give it a close time"));
}

}  // namespace scene_motion_test
}  // namespace nimbus::test

namespace nimbus::test {
namespace scene_motion_test {

TEST(SceneMotion, CameraAndLightsMoveRigidly) {
  const SceneDesc scene = parse_ok(
      "camera:\n  shutter: { close: 2 }\n"
      "  motion: [{ time: 0 }, { time: 2, translate: [1, 0, 0], rotate: [0, 0, 30] }]\n"
      "lights:\n"
      "  - { type: point, position: [0, 0, 3], motion: [{ time: 0 }, { time: 2, translate: [0, 2, 0] }] }\n"
      "  - { type: spot, position: [0, 0, 3], direction: [0, 0, -1], motion: [{ time: 1 }] }\n");
  ASSERT_TRUE(scene.camera.motion);
  EXPECT_TRUE(scene.camera.motion->moves());
  EXPECT_NEAR(scene.camera.motion->at(1.0f).point({0, 0, 0}).x, 0.5f, 1e-5f);
  ASSERT_TRUE(scene.lights[0].motion);
  EXPECT_NEAR(scene.lights[0].motion->at(2.0f).point({0, 0, 3}).y, 2.0f, 1e-5f);
  ASSERT_TRUE(scene.lights[1].motion);
  EXPECT_FALSE(scene.lights[1].motion->moves()) << "one key holds still";
}

TEST(SceneMotion, CameraAndLightMistakesAreNamedWhereTheyAre) {
  // A scale would change the camera's field of view or the light's emission over the shutter.
  EXPECT_TRUE(fails_at("camera:\n  shutter: { close: 1 }\n  motion: [{ time: 0 }, { time: 1, scale: 2 }]\n",
                       3, 25, "camera.motion[1]", "the camera moves rigidly: translate and rotate only"));
  EXPECT_TRUE(
      fails_at("camera:\n  shutter: { close: 1 }\nlights:\n"
               "  - { type: point, position: [0, 0, 1], motion: [{ time: 1 }, { time: 0.5 }] }\n",
               4, 71, "lights[0].motion[1].time", "keys out of order"));
  EXPECT_TRUE(
      fails_at("camera:\n  shutter: { close: 1 }\nlights:\n"
               "  - { type: spot, position: [0, 0, 1], direction: [0, 0, -1],\n"
               "      motion: [{ time: 0 }, { time: 1, matrix: [2, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, "
               "1] }] }\n",
               5, 29, "lights[0].motion[1]", "a light moves rigidly"));
  // Keys at two times need a shutter that lasts.
  EXPECT_TRUE(fails_at("camera:\n  motion: [{ time: 0 }, { time: 1 }]\n", 2, 33, "camera.motion[1].time",
                       "outside the shutter [0, 0]"));
  // A sun has no motion (the sky holds still over a shutter).
  EXPECT_TRUE(fails_at("lights:\n  - { type: sun, direction: [0, 0, -1], motion: [{ time: 0 }] }\n", 2, 41,
                       "lights[0].motion", "unknown key"));
}

}  // namespace scene_motion_test
}  // namespace nimbus::test
