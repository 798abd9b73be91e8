// Shared by the tests of OBJ files' .mtl materials: scenes around the room fixture
// (fixtures/obj_materials/room.obj) and one-triangle OBJ files with a .mtl file written by the test.
#pragma once

#include <string>

#include "scene_test_support.hpp"

namespace nimbus::test {

inline const std::string kRoomDir = kFixtures + "/obj_materials";
inline const std::string kRoomObj = kRoomDir + "/room.obj";

// A scene with a `white` material and one mesh object: `file: FILE` is at line 3, column 26.
inline std::string obj_object(const std::string &file, const std::string &extra = "") {
  return "materials: { white: { type: diffuse } }\nobjects:\n  - { shape: mesh, file: " + file + extra +
         " }\n";
}

// The scene material of the shape whose material has `name`; fails the test when there is none.
inline const MaterialDesc &material_named(const SceneDesc &scene, const std::string &name) {
  for (const MaterialDesc &m : scene.materials)
    if (m.name == name) return m;
  ADD_FAILURE() << "no material " << name;
  static const MaterialDesc none;
  return none;
}

// tri.obj (one triangle using `usemtl m`, naming m.mtl) and m.mtl holding `mtl`, in `dir`; returns the
// OBJ's path.
inline std::string write_triangle(const TempDir &dir, const std::string &mtl,
                                  const std::string &usemtl = "usemtl m\n") {
  dir.write("m.mtl", mtl);
  return dir.write("tri.obj", "mtllib m.mtl\n" + usemtl + "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
}

// The scene of an object made of tri.obj whose material `m` is `mtl` (`newmtl m` is prepended).
inline SceneDesc triangle_scene(const std::string &mtl, const std::string &extra = "") {
  TempDir dir;
  return parse_ok(obj_object(write_triangle(dir, "newmtl m\n" + mtl), extra));
}

}  // namespace nimbus::test
