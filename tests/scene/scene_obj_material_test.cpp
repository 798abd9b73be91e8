// OBJ files keep their .mtl materials: the room fixture split by material (diffuse, map_Kd, conductor,
// dielectric, emitter, faces without usemtl), each .mtl statement's mapping, materials made once per
// file, and `material:` / `emission:` on the object overriding them.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "obj_material_support.hpp"

namespace nimbus::test {
namespace scene_obj_material_test {

// The one material of the one-triangle scene.
MaterialDesc mapped(const std::string &mtl) {
  const SceneDesc scene = triangle_scene(mtl);
  EXPECT_EQ(scene.shapes.size(), 1u);
  return scene.shapes.empty() ? MaterialDesc{} : scene.materials.at(scene.shapes[0].material);
}

TEST(SceneObjMaterial, TheRoomIsSplitByMaterial) {
  const SceneDesc scene = parse_ok(obj_object(kRoomObj));
  // In the order each material first appears in room.obj; the floor comes before any usemtl.
  const std::vector<std::pair<std::string, size_t>> expected{
      {"room.obj#default", 2}, {"red", 2},  {"white", 4}, {"painted", 2}, {"lamp", 2},
      {"chrome", 2},           {"glass", 2}};
  ASSERT_EQ(scene.shapes.size(), expected.size());
  ASSERT_EQ(scene.materials.size(), 1 + expected.size());  // the scene's `white`, then the file's
  for (size_t i = 0; i < expected.size(); ++i) {
    const ShapeDesc &s = scene.shapes[i];
    EXPECT_EQ(scene.materials.at(s.material).name,
              expected[i].first == "white" ? "white-2" : expected[i].first);
    EXPECT_EQ(s.mesh.indices.size(), 3 * expected[i].second) << expected[i].first;
    // Each part keeps only its own vertices, with their uvs (every face of room.obj has them).
    EXPECT_EQ(s.mesh.positions.size(), 2 * expected[i].second) << expected[i].first;  // 4 per quad
    EXPECT_EQ(s.mesh.uvs.size(), s.mesh.positions.size());
    EXPECT_EQ(s.type, ShapeType::Mesh);
    EXPECT_EQ(s.where.line, 3);
  }
  // The red wall is the face at x = -1.
  for (const Vec3f &p : scene.shapes[1].mesh.positions) EXPECT_EQ(p.x, -1);
}

TEST(SceneObjMaterial, TheRoomsMaterials) {
  const SceneDesc scene = parse_ok(obj_object(kRoomObj));
  const MaterialDesc &floor = material_named(scene, "room.obj#default");
  EXPECT_EQ(floor.type, MaterialType::Diffuse);
  expect_vec(floor.albedo, Rgb(0.8f));

  const MaterialDesc &red = material_named(scene, "red");
  EXPECT_EQ(red.type, MaterialType::Diffuse);
  expect_vec(red.albedo, {0.8f, 0.1f, 0.1f});
  EXPECT_FALSE(red.textured());
  expect_vec(material_named(scene, "white-2").albedo, Rgb(0.7f));  // "Kd 0.7": grey

  const MaterialDesc &painted = material_named(scene, "painted");
  EXPECT_EQ(painted.type, MaterialType::Diffuse);
  EXPECT_EQ(painted.albedo_texture.path,
            std::filesystem::path(kRoomDir + "/checker.ppm").lexically_normal().string());
  EXPECT_EQ(painted.albedo_texture.key, "objects[0].file");
  EXPECT_EQ(painted.albedo_texture.where.line, 3);
  EXPECT_EQ(painted.albedo_texture.where.column, 26);

  const MaterialDesc &chrome = material_named(scene, "chrome");
  EXPECT_EQ(chrome.type, MaterialType::Conductor);
  EXPECT_TRUE(chrome.use_reflectance);
  expect_vec(chrome.reflectance, {0.9f, 0.8f, 0.7f});
  EXPECT_NEAR(chrome.roughness, std::sqrt(0.1f), 1e-6f);  // Ns 198: alpha = sqrt(2 / 200) = r^2

  const MaterialDesc &glass = material_named(scene, "glass");
  EXPECT_EQ(glass.type, MaterialType::Dielectric);
  EXPECT_FLOAT_EQ(glass.ior, 1.45f);
  EXPECT_EQ(glass.roughness, 0);  // no Ns: smooth
  EXPECT_FALSE(glass.dispersive());

  // Only the lamp emits, by its Ke; one-sided and in its own LightMix group, like any emitter.
  for (const ShapeDesc &s : scene.shapes) {
    const bool lamp = scene.materials[s.material].name == "lamp";
    expect_vec(s.emission, lamp ? Rgb(8.0f) : Rgb(0.0f));
    EXPECT_FALSE(s.two_sided);
    EXPECT_EQ(s.group, "");
  }
  expect_vec(material_named(scene, "lamp").albedo, Rgb(0.2f));
}

TEST(SceneObjMaterial, TheMtlFileIsRecordedAsASource) {
  const SceneDesc scene = parse_ok(obj_object(kRoomObj));
  std::vector<std::string> names;
  for (const SourceFile &f : scene.sources)
    names.push_back(std::filesystem::path(f.path).filename().string());
  EXPECT_EQ(names, (std::vector<std::string>{"test.yaml", "room.obj", "room.mtl"}));
}

TEST(SceneObjMaterial, MaterialsAreMadeOncePerFile) {
  const SceneDesc scene = parse_ok(
      "meshes:\n  room: { file: " + kRoomObj + " }\nobjects:\n" + "  - { shape: instance, mesh: room }\n" +
      "  - { shape: instance, mesh: room, transform: { translate: [5, 0, 0] } }\n" +
      "  - { shape: mesh, file: " + kRoomObj + " }\n");
  ASSERT_EQ(scene.shapes.size(), 21u);
  EXPECT_EQ(scene.materials.size(), 7u);
  for (size_t i = 0; i < 7; ++i) {
    EXPECT_EQ(scene.shapes[i].material, scene.shapes[i + 7].material);
    EXPECT_EQ(scene.shapes[i].material, scene.shapes[i + 14].material);
  }
  EXPECT_EQ(scene.shapes[8].mesh.positions[0].x, scene.shapes[1].mesh.positions[0].x + 5);
  // The warning about room.mtl's ignored statements is given once, at the first object that uses it.
  ASSERT_EQ(scene.warnings.size(), 1u);
  EXPECT_EQ(scene.warnings[0].rfind("test.yaml:4:", 0), 0u) << scene.warnings[0];
}

TEST(SceneObjMaterial, NamesAreMadeUniqueAgainstTheScenes) {
  const SceneDesc scene = parse_ok(
      "materials:\n  red: { type: diffuse }\n  red-2: { type: diffuse }\nobjects:\n  - { shape: mesh, "
      "file: " +
      kRoomObj + " }\n");
  EXPECT_EQ(scene.materials.at(scene.shapes.at(1).material).name, "red-3");
  expect_vec(scene.materials.at(scene.shapes.at(1).material).albedo, {0.8f, 0.1f, 0.1f});
}

TEST(SceneObjMaterial, MaterialKeyOverridesTheMtl) {
  const SceneDesc scene = parse_ok(obj_object(kRoomObj, ", material: white"));
  ASSERT_EQ(scene.shapes.size(), 1u);  // one mesh, as without .mtl materials
  EXPECT_EQ(scene.shapes[0].material, 0u);
  EXPECT_EQ(scene.shapes[0].mesh.indices.size(), 3u * 16);
  expect_vec(scene.shapes[0].emission, Rgb(0.0f));  // the lamp's Ke too
  EXPECT_EQ(scene.materials.size(), 1u);
  EXPECT_TRUE(scene.warnings.empty());  // what is not used is not warned about
}

TEST(SceneObjMaterial, ObjectEmissionOverridesKe) {
  const SceneDesc scene = parse_ok(obj_object(kRoomObj, ", emission: { radiance: [1, 2, 3] }, group: room"));
  ASSERT_EQ(scene.shapes.size(), 7u);
  for (const ShapeDesc &s : scene.shapes) {
    expect_vec(s.emission, {1, 2, 3});
    EXPECT_EQ(s.group, "room");
  }
}

TEST(SceneObjMaterial, TheObjectsKeysApplyToEveryPart) {
  const SceneDesc scene =
      parse_ok(obj_object(kRoomObj, ", two_sided: true, group: lamps, transform: { translate: [0, 0, 1] }"));
  ASSERT_EQ(scene.shapes.size(), 7u);
  for (const ShapeDesc &s : scene.shapes) {
    EXPECT_TRUE(s.two_sided);
    EXPECT_EQ(s.group, "lamps");
    for (const Vec3f &p : s.mesh.positions) EXPECT_GE(p.z, 1);
  }
}

TEST(SceneObjMaterial, DiffuseFromKd) {
  MaterialDesc m = mapped("Kd 0.2 0.3 0.4\n");
  EXPECT_EQ(m.type, MaterialType::Diffuse);
  EXPECT_EQ(m.name, "m");
  expect_vec(m.albedo, {0.2f, 0.3f, 0.4f});
  expect_vec(mapped("Kd 2 -1 0.5\n").albedo, {1, 0, 0.5f});  // clamped to [0, 1]
  expect_vec(mapped("illum 2\n").albedo, Rgb(0.8f));         // no Kd
  // Ks that does not outweigh Kd leaves it diffuse.
  EXPECT_EQ(mapped("Kd 0.8\nKs 0.5\nNs 100\n").type, MaterialType::Diffuse);
}

TEST(SceneObjMaterial, DiffuseTextureFromMapKd) {
  // Relative to the .mtl file; the rest of the line is the name (spaces kept, backslashes as separators).
  const TempDir dir;
  const std::string obj = write_triangle(dir, "newmtl m\nmap_Kd -o 0.5 0.5 -clamp on maps\\a b.png\n");
  const SceneDesc scene = parse_ok(obj_object(obj));
  const MaterialDesc &m = scene.materials.at(scene.shapes.at(0).material);
  EXPECT_EQ(m.albedo_texture.path, (dir.path() / "maps/a b.png").lexically_normal().string());
  ASSERT_EQ(scene.warnings.size(), 1u);
  EXPECT_NE(scene.warnings[0].find(": map_Kd -o, map_Kd -clamp"), std::string::npos) << scene.warnings[0];
}

TEST(SceneObjMaterial, ConductorFromKsOrIllum3) {
  MaterialDesc m = mapped("Kd 0.1\nKs 0.9 0.8 0.7\n");
  EXPECT_EQ(m.type, MaterialType::Conductor);
  EXPECT_TRUE(m.use_reflectance);
  expect_vec(m.reflectance, {0.9f, 0.8f, 0.7f});
  EXPECT_EQ(m.roughness, 0);  // no Ns: a mirror
  m = mapped("Kd 0.9\nKs 1.5 0.5 0.5\nillum 3\nNs 2\n");
  EXPECT_EQ(m.type, MaterialType::Conductor);
  expect_vec(m.reflectance, {1, 0.5f, 0.5f});
  EXPECT_NEAR(m.roughness, std::sqrt(std::sqrt(0.5f)), 1e-6f);  // alpha = sqrt(2 / 4)
  EXPECT_NEAR(mapped("Ks 1\nNs 0\n").roughness, 1, 1e-6f);
  EXPECT_NEAR(mapped("Ks 1\nNs -5\n").roughness, 1, 1e-6f);  // a negative exponent taken as 0
  EXPECT_LT(mapped("Ks 1\nNs 1e6\n").roughness, 0.04f);
}

TEST(SceneObjMaterial, DielectricFromTransmission) {
  for (const char *mtl : {"illum 4\n", "illum 6\n", "illum 7\n", "d 0.5\n", "Tr 0.3\n", "Tf 0.5 0.9 0.9\n",
                          "d 0.9\nTr 0\n", "Kd 0.1\nKs 0.9\nd 0.5\n"})
    EXPECT_EQ(mapped(mtl).type, MaterialType::Dielectric) << mtl;
  // Opaque: `d` wins over `Tr` (exporters disagree on what Tr means), and a white or black Tf is no
  // transmission (many exporters write Tf 1 1 1 on every material; Tf 0 0 0 passes no light).
  for (const char *mtl : {"d 1\nTr 0.7\n", "Tr 0.7\nd 1\n", "Tf 1 1 1\n", "Tf 0 0 0\n", "d 1\n", "illum 2\n"})
    EXPECT_EQ(mapped(mtl).type, MaterialType::Diffuse) << mtl;

  MaterialDesc m = mapped("illum 7\nNi 1.33\nNs 198\n");
  EXPECT_FLOAT_EQ(m.ior, 1.33f);
  EXPECT_NEAR(m.roughness, std::sqrt(0.1f), 1e-6f);
  EXPECT_FLOAT_EQ(mapped("illum 7\n").ior, 1.5f);        // no Ni
  EXPECT_FLOAT_EQ(mapped("illum 7\nNi 1\n").ior, 1.5f);  // Ni <= 1: no glass has it
  EXPECT_FLOAT_EQ(mapped("illum 7\nNi 0.5\n").ior, 1.5f);
  EXPECT_FLOAT_EQ(mapped("illum 7\nNi 25\n").ior, 10.0f);  // as written materials, at most 10
  EXPECT_EQ(mapped("illum 7\n").roughness, 0);
}

TEST(SceneObjMaterial, EmitterFromKe) {
  SceneDesc scene = triangle_scene("Kd 0.5\nKe 2 0 -1\n");
  ASSERT_EQ(scene.shapes.size(), 1u);
  expect_vec(scene.shapes[0].emission, {2, 0, 0});  // negative radiance is none
  scene = triangle_scene("Ke 0 0 0\n");
  expect_vec(scene.shapes.at(0).emission, Rgb(0.0f));
  // A moving or deforming object may take a material that does not emit.
  scene = triangle_scene("Kd 0.5\n", ", motion: [{ time: 0, translate: [0, 0, 0] }]");
  EXPECT_TRUE(scene.shapes.at(0).motion);
}

TEST(SceneObjMaterial, KaIsIgnoredWithoutWarning) {
  const SceneDesc scene = triangle_scene("Ka 20 20 20\nKd 1 1 1\n");  // Embree's cornell_box.mtl light
  EXPECT_TRUE(scene.warnings.empty());
  expect_vec(scene.shapes.at(0).emission, Rgb(0.0f));
  expect_vec(scene.materials.at(scene.shapes.at(0).material).albedo, Rgb(1.0f));
}

TEST(SceneObjMaterial, EveryFileOfAnMtllibIsRead) {
  // tinyobjloader alone would stop at the first file it can read.
  const TempDir dir;
  dir.write("a.mtl", "newmtl a\nKd 1 0 0\n");
  dir.write("b.mtl", "newmtl b\nKd 0 1 0\n");
  const std::string obj = dir.write(
      "two.obj", "mtllib a.mtl b.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl b\nf 1 2 3\nusemtl a\nf 1 3 2\n");
  const SceneDesc scene = parse_ok(obj_object(obj));
  ASSERT_EQ(scene.shapes.size(), 2u);
  EXPECT_EQ(scene.materials.at(scene.shapes[0].material).name, "b");
  EXPECT_EQ(scene.materials.at(scene.shapes[1].material).name, "a");
}

TEST(SceneObjMaterial, SubdivisionSurfacesIgnoreMaterials) {
  // Even a .mtl file that does not exist: the cage's materials are never read.
  const TempDir dir;
  const std::string obj =
      dir.write("cage.obj", "mtllib missing.mtl\nusemtl m\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
  const SceneDesc scene = parse_ok(
      "materials: { white: { type: diffuse } }\nobjects:\n"
      "  - { shape: subdivision, material: white, level: 1, file: " +
      obj + " }\n");
  ASSERT_EQ(scene.shapes.size(), 1u);
  EXPECT_EQ(scene.shapes[0].material, 0u);
  EXPECT_TRUE(scene.warnings.empty());
}

}  // namespace scene_obj_material_test
}  // namespace nimbus::test
