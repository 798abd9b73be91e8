// `meshes:` and `shape: instance` — named meshes, each placed by any number of objects with their own
// transform and material; each mesh file read once.
#include <gtest/gtest.h>

#include "scene/mesh_library.hpp"
#include "scene_test_support.hpp"

namespace nimbus::test {
namespace scene_instance_test {

const std::string kTwoMaterials =
    "materials:\n  white: { type: diffuse }\n  red: { type: diffuse, albedo: [1, 0, 0] }\n";

TEST(SceneInstance, EachInstanceIsATransformedCopy) {
  const SceneDesc scene = parse_ok(kTwoMaterials + R"(meshes:
  tri: { positions: [[0, 0, 0], [1, 0, 0], [0, 1, 0]], indices: [0, 1, 2] }
objects:
  - { shape: instance, mesh: tri, material: white }
  - { shape: instance, mesh: tri, material: red, transform: { translate: [0, 0, 2], scale: 2 } }
)");
  ASSERT_EQ(scene.shapes.size(), 2u);  // the named mesh itself places nothing
  const MeshData &a = scene.shapes[0].mesh, &b = scene.shapes[1].mesh;
  EXPECT_EQ(scene.shapes[0].type, ShapeType::Mesh);
  EXPECT_EQ(scene.shapes[0].material, 0u);
  EXPECT_EQ(scene.shapes[1].material, 1u);
  ASSERT_EQ(a.positions.size(), 3u);
  ASSERT_EQ(b.positions.size(), 3u);
  EXPECT_EQ(a.indices, b.indices);
  for (size_t i = 0; i < 3; ++i) EXPECT_EQ(b.positions[i], a.positions[i] * 2.0f + Vec3f(0, 0, 2));
}

TEST(SceneInstance, NamedMeshFromAFileAndPlainMeshesShareTheFile) {
  const std::string obj = kFixtures + "/meshes/quad.obj";
  const SceneDesc scene = parse_ok(kTwoMaterials + "meshes:\n  quad: { file: " + obj + " }\nobjects:\n" +
                                   "  - { shape: instance, mesh: quad, material: white }\n" +
                                   "  - { shape: mesh, file: " + obj + ", material: red }\n");
  ASSERT_EQ(scene.shapes.size(), 2u);
  EXPECT_EQ(scene.shapes[0].mesh.positions, scene.shapes[1].mesh.positions);
  EXPECT_EQ(scene.shapes[0].mesh.normals.size(), 4u);
}

// The library hands out the same loaded mesh for every spelling of a file's path.
TEST(SceneInstance, EachFileIsLoadedOnce) {
  scene_yaml::SceneSource source{"test.yaml", kFixtures, {}};
  const auto value = [&](const std::string &text) {
    return scene_yaml::YamlValue(source, YAML::Load(text), "file", YAML::Mark());
  };
  scene_yaml::MeshLibrary library;
  const auto first = library.load(value("meshes/quad.obj"));
  EXPECT_EQ(library.load(value("meshes/../meshes/quad.obj")).get(), first.get());
  EXPECT_EQ(library.load(value(kFixtures + "/meshes/quad.obj")).get(), first.get());
  EXPECT_NE(library.load(value("meshes/pentagon.obj")).get(), first.get());
}

TEST(SceneInstanceErrors, UnknownMeshName) {
  EXPECT_TRUE(
      fails_at(kTwoMaterials +
                   "meshes:\n  chair: { positions: [[0, 0, 0], [1, 0, 0], [0, 1, 0]], indices: [0, 1, 2] }\n"
                   "objects:\n  - { shape: instance, mesh: chiar, material: white }\n",
               7, 30, "objects[0].mesh", "unknown mesh 'chiar'; defined: chair"));
  EXPECT_TRUE(fails_at(kTwoMaterials + "objects:\n  - { shape: instance, mesh: chair, material: white }\n", 5,
                       30, "objects[0].mesh", "unknown mesh 'chair': the scene defines no meshes"));
}

TEST(SceneInstanceErrors, InstanceKeys) {
  EXPECT_TRUE(fails_at(kTwoMaterials + "objects:\n  - { shape: instance, material: white }\n", 5, 5,
                       "objects[0].mesh", "missing required key 'mesh'"));
  EXPECT_TRUE(
      fails_at(kTwoMaterials + "objects:\n  - { shape: instance, mesh: m, file: a.obj, material: white }\n",
               5, 33, "objects[0].file", "unknown key 'file' for an instance"));
}

TEST(SceneInstanceErrors, MeshEntryKeys) {
  EXPECT_TRUE(fails_at("meshes:\n  m: { file: a.obj, material: white }\n", 2, 21, "meshes.m.material",
                       "unknown key 'material'; allowed: file, positions, indices, normals, uvs"));
  EXPECT_TRUE(fails_at("meshes:\n  m: { file: a.ply }\n", 2, 14, "meshes.m.file",
                       "unknown mesh file type '.ply'; supported: .obj, .gltf, .glb"));
  EXPECT_TRUE(fails_at("meshes:\n  - { file: a.obj }\n", 2, 3, "meshes", "expected a map, got a sequence"));
}

TEST(SceneInstanceErrors, MeshDefinedTwiceAcrossFiles) {
  TempDir dir;
  const std::string tri = "{ positions: [[0, 0, 0], [1, 0, 0], [0, 1, 0]], indices: [0, 1, 2] }";
  const std::string main = dir.write("main.yaml", "meshes:\n  tri: " + tri + "\ninclude: [more.yaml]\n");
  const std::string more = dir.write("more.yaml", "meshes:\n  tri: " + tri + "\n");
  EXPECT_TRUE(error_is(parse_scene_file(main), more, 2, 3, "meshes.tri",
                       "mesh 'tri' is already defined at " + main + ":2:3"));
}

}  // namespace scene_instance_test
}  // namespace nimbus::test
