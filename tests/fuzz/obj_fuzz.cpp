// The OBJ reader (scene/obj_loader.hpp) and the .mtl files an OBJ names: the input is mesh.obj, followed
// after a line "#--8<--" by mesh.mtl (which the OBJ may name with `mtllib mesh.mtl`). It is read as a
// triangle mesh and as a polygon cage. The reader's errors hold the reason only, one line; its faces by
// material cover every triangle once; in a scene (`shape: mesh, file: mesh.obj`) a file the reader
// refused, or whose materials it could not use, must be refused too, with the scene's position and the
// mesh's path.
#include <cstdint>
#include <string>
#include <vector>

#include "fuzz_support.hpp"
#include "scene/obj_loader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  using namespace nimbus::fuzz;
  const std::vector<std::string> parts = split_parts(data, size, "#--8<--", 2);
  const std::filesystem::path obj = scratch_dir() / "mesh.obj", mtl = scratch_dir() / "mesh.mtl";
  write_file(obj, parts[0]);
  if (parts.size() > 1) {
    write_file(mtl, parts[1]);
  } else {
    std::error_code ec;
    std::filesystem::remove(mtl, ec);  // not the previous input's
  }

  const nimbus::Expected<nimbus::ObjMesh> mesh = nimbus::load_obj_mesh(obj, nullptr);
  if (!mesh) check_error_line(mesh.error().message, "");
  if (mesh) {
    if (!mesh->materials.error.empty()) check_error_line(mesh->materials.error, "");
    std::vector<int> covered(mesh->mesh.indices.size() / 3, 0);
    for (const nimbus::ObjPart &part : mesh->parts) {
      require(part.material < int(mesh->materials.materials.size()), "a part names no material");
      for (uint32_t t : part.triangles) {
        require(t < covered.size(), "a part names a triangle the mesh does not have");
        ++covered[t];
      }
    }
    for (int c : covered) require(c == 1, "the parts do not cover every triangle exactly once");
  }
  const nimbus::Expected<nimbus::PolygonMesh> cage = nimbus::load_obj_polygons(obj, nullptr);
  if (!cage) check_error_line(cage.error().message, "");

  const std::optional<std::string> error = scene_error("objects: [{shape: mesh, file: mesh.obj}]\n");
  if (!mesh || !mesh->materials.error.empty()) {
    require(error.has_value(), "the scene accepted an OBJ file (or its materials) the reader refused");
    check_error_line(*error, obj.string());
  }
  return 0;
}
