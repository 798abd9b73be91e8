// OBJ meshes: loading, triangulation, per-vertex attributes, and paths relative to the scene file.
#include <gtest/gtest.h>

#include <filesystem>

#include "scene_test_support.hpp"

namespace nimbus::test {
namespace scene_mesh_test {

std::string mesh_object(const std::string &file, const std::string &extra = "") {
  return "materials: { white: { type: diffuse } }\nobjects:\n  - { shape: mesh, material: white, file: " +
         file + extra + " }\n";
}

TEST(SceneMesh, ObjQuadWithNormalsAndUvs) {
  const SceneDesc scene = parse_ok(mesh_object(kFixtures + "/meshes/quad.obj"));
  ASSERT_EQ(scene.shapes.size(), 1u);
  const MeshData &mesh = scene.shapes[0].mesh;
  EXPECT_EQ(scene.shapes[0].type, ShapeType::Mesh);
  ASSERT_EQ(mesh.positions.size(), 4u);  // one vertex per distinct (position, normal, uv) corner
  ASSERT_EQ(mesh.indices.size(), 6u);
  ASSERT_EQ(mesh.normals.size(), 4u);
  ASSERT_EQ(mesh.uvs.size(), 4u);
  for (size_t i = 0; i < 4; ++i) {
    expect_vec(mesh.normals[i], {0, 0, 1});  // "vn 0 0 2", normalised
    // Each uv was written to match its corner: uv = (p + 1) / 2.
    EXPECT_NEAR(mesh.uvs[i].x, (mesh.positions[i].x + 1) / 2, 1e-6f);
    EXPECT_NEAR(mesh.uvs[i].y, (mesh.positions[i].y + 1) / 2, 1e-6f);
  }
  for (size_t t = 0; t < 2; ++t) {
    const Vec3f &p0 = mesh.positions[mesh.indices[3 * t]];
    const Vec3f n =
        cross(mesh.positions[mesh.indices[3 * t + 1]] - p0, mesh.positions[mesh.indices[3 * t + 2]] - p0);
    EXPECT_GT(n.z, 0) << "winding of the OBJ face is kept";
  }
}

TEST(SceneMesh, ObjIsTransformedToWorldSpace) {
  const SceneDesc scene = parse_ok(mesh_object(kFixtures + "/meshes/quad.obj",
                                               ", transform: { rotate: [90, 0, 0], translate: [0, 0, 1] }"));
  const MeshData &mesh = scene.shapes.at(0).mesh;
  for (const Vec3f &n : mesh.normals) expect_vec(n, {0, -1, 0});
  for (const Vec3f &p : mesh.positions) EXPECT_NEAR(p.y, 0, 1e-6f);
}

TEST(SceneMesh, ObjPolygonIsFanTriangulatedWithoutNormals) {
  const SceneDesc scene = parse_ok(mesh_object(kFixtures + "/meshes/pentagon.obj"));
  const MeshData &mesh = scene.shapes.at(0).mesh;
  EXPECT_EQ(mesh.positions.size(), 5u);
  EXPECT_EQ(mesh.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3, 0, 3, 4}));
  EXPECT_TRUE(mesh.normals.empty());
  EXPECT_TRUE(mesh.uvs.empty());
}

TEST(SceneMesh, ObjPathIsRelativeToTheSceneFile) {
  // The test runs in the build tree; the mesh is found next to the scene file, not in the current directory.
  const std::string path = kFixtures + "/mesh_scene.yaml";
  ASSERT_NE(std::filesystem::current_path(), std::filesystem::path(kFixtures));
  const Expected<SceneDesc> scene = parse_scene_file(path);
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  EXPECT_EQ(scene->path, path);
  ASSERT_EQ(scene->shapes.size(), 1u);
  EXPECT_EQ(scene->shapes[0].mesh.indices.size(), 6u);
  for (const Vec3f &p : scene->shapes[0].mesh.positions) EXPECT_FLOAT_EQ(p.z, 1);
  EXPECT_EQ(scene->shapes[0].where.file, path);
  EXPECT_EQ(scene->shapes[0].where.line, 5);
}

TEST(SceneMesh, InlineSceneTextResolvesAgainstTheCurrentDirectory) {
  const std::filesystem::path previous = std::filesystem::current_path();
  std::filesystem::current_path(kFixtures);
  const Expected<SceneDesc> scene = parse_scene_string(mesh_object("meshes/quad.obj"), "inline.yaml");
  std::filesystem::current_path(previous);
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  EXPECT_EQ(scene->shapes.at(0).mesh.positions.size(), 4u);

  // From elsewhere the same relative path is not found, and the error says where it looked.
  EXPECT_TRUE(fails_at(mesh_object("meshes/quad.obj"), 3, 43, "objects[0].file",
                       "cannot load mesh 'meshes/quad.obj': No such file or directory"));
}

TEST(SceneMesh, ObjCannotBeCombinedWithInlineArrays) {
  const std::string obj = kFixtures + "/meshes/quad.obj";
  // `file: ` ends at column 42; the key after it follows the path and ", ".
  EXPECT_TRUE(fails_at(mesh_object(obj, ", indices: [0, 1, 2]"), 3, 45 + int(obj.size()),
                       "objects[0].indices", "cannot be combined with 'file'"));
}

}  // namespace scene_mesh_test
}  // namespace nimbus::test
