// `include:` — files appended to the scene, paths relative to the including file, errors located in the
// file they are in, duplicate names and cycles.
#include <gtest/gtest.h>

#include "scene_test_support.hpp"

namespace nimbus::test {
namespace scene_include_test {

const std::string kQuadObj = "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n";

TEST(SceneInclude, SectionsAreAppendedAndNamesShared) {
  TempDir dir;
  const std::string main = dir.write("main.yaml", R"(include: [parts/materials.yaml, parts/room.yaml]
materials:
  white: { type: diffuse }
objects:
  - { shape: sphere, radius: 1, material: red }
lights:
  - { type: point, position: [0, 0, 3] }
)");
  dir.write("parts/materials.yaml", "materials:\n  red: { type: diffuse, albedo: [0.8, 0.1, 0.1] }\n");
  // Paths inside an included file (meshes, further includes) resolve against its own directory.
  dir.write("parts/room.yaml", R"(include: lamps/lamp.yaml
objects:
  - { shape: mesh, file: quad.obj, material: white }
)");
  dir.write("parts/quad.obj", kQuadObj);
  dir.write("parts/lamps/lamp.yaml", "lights:\n  - { type: sun, direction: [0, 0, -1] }\n");

  const Expected<SceneDesc> scene = parse_scene_file(main);
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  ASSERT_EQ(scene->materials.size(), 2u);
  EXPECT_EQ(scene->materials[0].name, "white");  // the main file's own items first
  EXPECT_EQ(scene->materials[1].name, "red");
  ASSERT_EQ(scene->shapes.size(), 2u);
  EXPECT_EQ(scene->shapes[0].type, ShapeType::Sphere);
  EXPECT_EQ(scene->shapes[0].material, 1u);
  EXPECT_EQ(scene->shapes[1].type, ShapeType::Mesh);
  EXPECT_EQ(scene->shapes[1].mesh.indices.size(), 6u);
  EXPECT_EQ(scene->shapes[1].where.file, (dir.path() / "parts/room.yaml").string());
  EXPECT_EQ(scene->shapes[1].where.line, 3);
  ASSERT_EQ(scene->lights.size(), 2u);
  EXPECT_EQ(scene->lights[0].type, LightType::Point);
  EXPECT_EQ(scene->lights[1].type, LightType::Sun);
  EXPECT_EQ(scene->lights[1].where.file, (dir.path() / "parts/lamps/lamp.yaml").string());
}

TEST(SceneInclude, AFileIncludedTwiceIsReadOnce) {
  TempDir dir;
  const std::string main = dir.write("main.yaml", "include: [a.yaml, b.yaml]\n");
  dir.write("a.yaml", "include: [common.yaml]\n");
  dir.write("b.yaml", "include: [./common.yaml]\nobjects:\n  - { shape: disk, radius: 1, material: grey }\n");
  dir.write("common.yaml", "materials:\n  grey: { type: diffuse, albedo: 0.5 }\n");
  const Expected<SceneDesc> scene = parse_scene_file(main);
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  EXPECT_EQ(scene->materials.size(), 1u);
  EXPECT_EQ(scene->shapes.size(), 1u);
}

TEST(SceneIncludeErrors, ErrorsNameTheIncludedFile) {
  TempDir dir;
  const std::string main =
      dir.write("main.yaml", "materials:\n  white: { type: diffuse }\ninclude: [objects.yaml]\n");
  const std::string objects =
      dir.write("objects.yaml", "objects:\n  - shape: sphere\n    radius: -1\n    material: white\n");
  EXPECT_TRUE(error_is(parse_scene_file(main), objects, 3, 13, "objects[0].radius", "must be > 0 (got -1)"));

  const std::string syntax = dir.write("objects.yaml", "objects:\n  - { shape: sphere, radius: 1\n");
  EXPECT_TRUE(error_is(parse_scene_file(main), syntax, 3, 1, "YAML syntax", "end of map flow"));
}

TEST(SceneIncludeErrors, MaterialDefinedTwiceNamesBothPlaces) {
  TempDir dir;
  const std::string main =
      dir.write("main.yaml", "include: [more.yaml]\nmaterials:\n  white: { type: diffuse }\n");
  const std::string more = dir.write("more.yaml", "materials:\n  white: { type: diffuse, albedo: 0.9 }\n");
  EXPECT_TRUE(error_is(parse_scene_file(main), more, 2, 10, "materials.white",
                       "material 'white' is already defined at " + main + ":3:10"));
}

TEST(SceneIncludeErrors, Cycles) {
  TempDir dir;
  const std::string a = dir.write("a.yaml", "include: [sub/b.yaml]\n");
  const std::string b = dir.write("sub/b.yaml", "include:\n  - ../a.yaml\n");
  EXPECT_TRUE(
      error_is(parse_scene_file(a), b, 2, 5, "include[0]", "include cycle: " + a + " -> " + b + " -> " + a));
  const std::string self = dir.write("self.yaml", "include: self.yaml\n");
  EXPECT_TRUE(
      error_is(parse_scene_file(self), self, 1, 10, "include", "include cycle: " + self + " -> " + self));
}

TEST(SceneIncludeErrors, MissingIncludedFile) {
  TempDir dir;
  const std::string main = dir.write("main.yaml", "include: [parts/none.yaml]\n");
  EXPECT_TRUE(error_is(parse_scene_file(main), main, 1, 11, "include[0]",
                       "cannot read included file '" + (dir.path() / "parts/none.yaml").string() +
                           "': No such file or directory"));
}

TEST(SceneIncludeErrors, OnlyTheMainFileSetsRenderCameraAndEnvironment) {
  TempDir dir;
  const std::string main = dir.write("main.yaml", "include: [part.yaml]\n");
  for (const char *section : {"render", "camera", "environment"}) {
    const std::string part = dir.write("part.yaml", "lights: []\n" + std::string(section) + ": {}\n");
    EXPECT_TRUE(error_is(parse_scene_file(main), part, 2, 1, section,
                         "only the main scene file may set '" + std::string(section) +
                             "'; an included file may hold: materials, meshes, objects, lights, include"));
  }
  const std::string part = dir.write("part.yaml", "textures: {}\n");
  EXPECT_TRUE(error_is(parse_scene_file(main), part, 1, 1, "textures", "unknown key 'textures'"));
}

TEST(SceneIncludeErrors, IncludeMustNameFiles) {
  EXPECT_TRUE(fails_at("include: [\"\"]\n", 1, 11, "include[0]", "must not be empty"));
  EXPECT_TRUE(fails_at("include: { file: a.yaml }\n", 1, 10, "include", "expected a sequence, got a map"));
}

}  // namespace scene_include_test
}  // namespace nimbus::test
