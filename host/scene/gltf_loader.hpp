// glTF 2.0 files (.gltf with its buffers, or .glb) as one triangle mesh, through tinygltf.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "core/expected.hpp"
#include "scene/scene_desc.hpp"
#include "scene/source_log.hpp"

namespace nimbus {

// The metallic-roughness parameters of a glTF material, as written (glTF's defaults where absent).
struct GltfMaterial {
  int index = -1;           // in the file's materials
  std::string name;         // may be empty
  Rgb base_color{1, 1, 1};  // baseColorFactor without alpha
  float metallic = 1, roughness = 1;
  std::string base_color_texture;  // absolute path of an external image; empty when none or embedded
};

struct GltfMesh {
  MeshData mesh;
  std::optional<GltfMaterial> material;  // that of the first triangle primitive, if it has one
};

// Every triangle primitive (triangles, strips and fans) reachable from the file's default scene (or from
// all root nodes when it names none; or every mesh once when the file has no nodes), with node transforms
// applied, merged into one mesh. Normals and uvs (TEXCOORD_0) are kept only when every primitive has them,
// since MeshData stores them per vertex; v is flipped (glTF's v = 0 is the top of the image, Nimbus's the
// bottom). Images are not decoded. On failure the Error holds the reason only; the caller adds the path.
// The file and every file tinygltf reads for it (buffers, images) are recorded in `log` (may be null).
Expected<GltfMesh> load_gltf_mesh(const std::filesystem::path &path, SourceLog *log);

}  // namespace nimbus
