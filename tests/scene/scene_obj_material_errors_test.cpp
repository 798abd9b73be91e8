// OBJ files' .mtl materials that cannot be used: the one warning per file naming what is ignored, and the
// errors, each at the value that named the mesh with the OBJ's and the .mtl file's paths.
#include <gtest/gtest.h>

#include <filesystem>

#include "obj_material_support.hpp"

namespace nimbus::test {
namespace scene_obj_material_errors_test {

// The error of a one-triangle object whose m.mtl holds `mtl`, reported at its `file:` (line 3, column 26).
::testing::AssertionResult mtl_fails(const std::string &mtl, const std::string &contains) {
  const TempDir dir;
  const std::string obj = write_triangle(dir, mtl);
  const std::string mtl_path = (dir.path() / "m.mtl").string();
  return fails_at(obj_object(obj), 3, 26, "objects[0].file",
                  "cannot use the materials of '" + obj + "': " + mtl_path + contains);
}

TEST(SceneObjMaterialWarnings, OneLineNamesTheFileAndTheIgnoredStatements) {
  const SceneDesc scene = parse_ok(obj_object(kRoomObj));
  ASSERT_EQ(scene.warnings.size(), 1u);
  EXPECT_EQ(scene.warnings[0],
            "test.yaml:3:26: warning: objects[0].file: " +
                std::filesystem::path(kRoomDir + "/room.mtl").lexically_normal().string() +
                ": ignores the .mtl statements Nimbus does not map: map_Kd -s, map_Bump, Pr, "
                "sharpness");
}

TEST(SceneObjMaterialWarnings, LongListsAreCutAndBytesShownSafely) {
  std::string mtl = "newmtl m\n";
  for (int i = 0; i < 20; ++i) mtl += "x" + std::to_string(i) + " 1\n";
  mtl += "bad\x01word 1\n";
  const TempDir dir;
  const SceneDesc scene = parse_ok(obj_object(write_triangle(dir, mtl)));
  ASSERT_EQ(scene.warnings.size(), 1u);
  EXPECT_NE(scene.warnings[0].find(": x0, x1, x2, x3, x4, x5, x6, x7, x8, x9, x10, x11 and 9 more"),
            std::string::npos)
      << scene.warnings[0];
  EXPECT_EQ(scene.warnings[0].find('\x01'), std::string::npos);
}

TEST(SceneObjMaterialWarnings, UsemtlOfAnUnknownNameGetsTheDefaultMaterial) {
  const TempDir dir;
  const std::string obj = write_triangle(dir, "newmtl m\nKd 1 0 0\n", "usemtl nosuch\n");
  const SceneDesc scene = parse_ok(obj_object(obj));
  ASSERT_EQ(scene.shapes.size(), 1u);
  EXPECT_EQ(scene.materials.at(scene.shapes[0].material).name, "tri.obj#default");
  EXPECT_EQ(scene.materials.at(scene.shapes[0].material).albedo, Rgb(0.8f));
  ASSERT_EQ(scene.warnings.size(), 1u);
  EXPECT_EQ(scene.warnings[0],
            "test.yaml:3:26: warning: objects[0].file: " + obj +
                ": usemtl names materials no .mtl file defines (their faces get the default "
                "material): nosuch");
}

TEST(SceneObjMaterialErrors, MissingMtlFile) {
  const TempDir dir;
  const std::string obj =
      dir.write("tri.obj", "mtllib nothere.mtl\nusemtl m\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_TRUE(fails_at(obj_object(obj), 3, 26, "objects[0].file",
                       "cannot use the materials of '" + obj + "': '" +
                           (dir.path() / "nothere.mtl").string() +
                           "': No such file or directory (an object with 'material:' needs none)"));
  // An object that assigns its material needs none of the file's.
  const SceneDesc scene = parse_ok(obj_object(obj, ", material: white"));
  EXPECT_EQ(scene.shapes.size(), 1u);
  EXPECT_TRUE(scene.warnings.empty());
}

TEST(SceneObjMaterialErrors, InstancesFailAtTheirMeshName) {
  const TempDir dir;
  const std::string obj = dir.write("tri.obj", "mtllib nothere.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_TRUE(
      fails_at("meshes:\n  tri: { file: " + obj + " }\nobjects:\n  - { shape: instance, mesh: tri }\n", 4, 30,
               "objects[0].mesh", "No such file or directory"));
}

TEST(SceneObjMaterialErrors, ObjWithoutMaterialsNeedsMaterialKey) {
  const std::string obj = kFixtures + "/meshes/pentagon.obj";
  EXPECT_TRUE(fails_at(
      "objects:\n  - { shape: mesh, file: " + obj + " }\n", 2, 5, "objects[0].material",
      "missing required key 'material': '" + obj + "' names no .mtl materials (mtllib) to take instead"));
  // A .mtl file without materials gives none either.
  const TempDir dir;
  const std::string empty = write_triangle(dir, "# nothing\n");
  EXPECT_TRUE(fails_at("objects:\n  - { shape: mesh, file: " + empty + " }\n", 2, 5, "objects[0].material",
                       "names no .mtl materials"));
}

TEST(SceneObjMaterialErrors, MalformedValues) {
  EXPECT_TRUE(mtl_fails("newmtl m\nKd red\n", ":2: Kd: expected a number, got 'red'"));
  EXPECT_TRUE(mtl_fails("newmtl m\nKd 1 0\n", ":2: Kd: expected r g b or one number, got 2 values"));
  EXPECT_TRUE(
      mtl_fails("newmtl m\n\nKs 1 1 1e999\n", ":3: Ks: '1e999' is not a finite single-precision number"));
  EXPECT_TRUE(mtl_fails("newmtl m\nKe nan\n", ":2: Ke: 'nan' is not a finite single-precision number"));
  EXPECT_TRUE(mtl_fails("newmtl m\nNs\n", ":2: Ns: expected one number, got 0 values"));
  EXPECT_TRUE(mtl_fails("newmtl m\nNi 1.5 2\n", ":2: Ni: expected one number, got 2 values"));
  EXPECT_TRUE(mtl_fails("newmtl m\nd 0.5x\n", ":2: d: expected a number, got '0.5x'"));
  EXPECT_TRUE(mtl_fails("newmtl m\nillum 2.5\n", ":2: illum: expected an integer, got '2.5'"));
  EXPECT_TRUE(mtl_fails("newmtl m\nmap_Kd\n", ":2: map_Kd: no file name"));
  EXPECT_TRUE(mtl_fails("Kd 1 1 1\nnewmtl m\n", ":1: Kd: comes before any 'newmtl'"));
  EXPECT_TRUE(mtl_fails("newmtl\n", ":1: newmtl: no material name"));
  EXPECT_TRUE(mtl_fails("newmtl m\nnewmtl m\n", ":2: newmtl: material 'm' is already defined on line 1"));
  // A trailing comment is no value; the spectral form is ignored with a warning, not an error.
  const SceneDesc scene = triangle_scene("Kd 1 0 0 # red\nKs spectral steel.rfl\n");
  EXPECT_EQ(scene.materials.at(scene.shapes.at(0).material).albedo, Rgb(1, 0, 0));
  ASSERT_EQ(scene.warnings.size(), 1u);
  EXPECT_NE(scene.warnings[0].find(": Ks spectral"), std::string::npos) << scene.warnings[0];
}

TEST(SceneObjMaterialErrors, NameDefinedByTwoFiles) {
  const TempDir dir;
  dir.write("a.mtl", "newmtl m\n");
  dir.write("b.mtl", "newmtl m\n");
  const std::string obj = dir.write("tri.obj", "mtllib a.mtl b.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_TRUE(fails_at(obj_object(obj), 3, 26, "objects[0].file",
                       "'" + (dir.path() / "b.mtl").string() + "': material 'm' is already defined in '" +
                           (dir.path() / "a.mtl").string() + "'"));
}

TEST(SceneObjMaterialErrors, AnEmittingMtlMaterialCannotMoveOrDeform) {
  const TempDir dir;
  const std::string obj = write_triangle(dir, "newmtl m\nKe 1 1 1\n");
  // `motion` and `deform` follow the path and ", " (the path starts at column 26).
  const int column = 28 + int(obj.size());
  EXPECT_TRUE(fails_at("camera: { shutter: { close: 1 } }\n" + obj_object(obj, ", motion: [{ time: 0 }]"), 4,
                       column, "objects[0].motion",
                       "an emitting object cannot move yet: its .mtl material 'm' emits (Ke)"));
  EXPECT_TRUE(fails_at(
      "camera: { shutter: { close: 1 } }\n" + obj_object(obj, ", deform: [" + obj + ", " + obj + "]"), 4,
      column, "objects[0].deform", "an emitting mesh cannot deform yet: its .mtl material 'm' emits (Ke)"));
}

}  // namespace scene_obj_material_errors_test
}  // namespace nimbus::test
