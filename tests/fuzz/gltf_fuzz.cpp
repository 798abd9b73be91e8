// The glTF reader (scene/gltf_loader.hpp): the input is mesh.glb when it starts with the binary magic
// "glTF", else mesh.gltf (JSON), since tinygltf picks the parser by extension. Buffers and images it
// names are looked up beside it in the scratch directory. As for OBJ, the reader's errors hold the
// reason only, one line, and a scene naming a refused file must be refused with the file's path.
#include <cstdint>
#include <cstring>
#include <string>

#include "fuzz_support.hpp"
#include "scene/gltf_loader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  using namespace nimbus::fuzz;
  const bool binary = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
  const std::string name = binary ? "mesh.glb" : "mesh.gltf";
  const std::filesystem::path file = scratch_dir() / name;
  write_file(file, std::string_view(reinterpret_cast<const char *>(data), size));

  const nimbus::Expected<nimbus::GltfMesh> mesh = nimbus::load_gltf_mesh(file, nullptr);
  if (!mesh) check_error_line(mesh.error().message, "");

  const std::optional<std::string> error = scene_error("objects: [{shape: mesh, file: " + name + "}]\n");
  if (!mesh) {
    require(error.has_value(), "the scene accepted a glTF file the reader refused");
    check_error_line(*error, file.string());
  }
  return 0;
}
