// The OBJ reader (scene/obj_loader.hpp): the input is mesh.obj, read as a triangle mesh and as a polygon
// cage. The reader's errors hold the reason only, one line; in a scene (`shape: mesh, file: mesh.obj`)
// a file the reader refused must be refused too, with the scene's position and the mesh's path.
#include <cstdint>
#include <string>

#include "fuzz_support.hpp"
#include "scene/obj_loader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  using namespace nimbus::fuzz;
  const std::filesystem::path obj = scratch_dir() / "mesh.obj";
  write_file(obj, std::string_view(reinterpret_cast<const char *>(data), size));

  const nimbus::Expected<nimbus::MeshData> mesh = nimbus::load_obj_mesh(obj, nullptr);
  if (!mesh) check_error_line(mesh.error().message, "");
  const nimbus::Expected<nimbus::PolygonMesh> cage = nimbus::load_obj_polygons(obj, nullptr);
  if (!cage) check_error_line(cage.error().message, "");

  const std::optional<std::string> error = scene_error("objects: [{shape: mesh, file: mesh.obj}]\n");
  if (!mesh) {
    require(error.has_value(), "the scene accepted an OBJ file the reader refused");
    check_error_line(*error, obj.string());
  }
  return 0;
}
