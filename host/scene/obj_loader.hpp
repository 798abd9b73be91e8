// Wavefront OBJ files as one triangle mesh, through tinyobjloader.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include "core/expected.hpp"
#include "scene/scene_desc.hpp"
#include "scene/source_log.hpp"

namespace nimbus {

// All groups and objects of the file merged into one mesh, in the file's coordinates; polygons are
// fan-triangulated (OBJ faces are expected to be convex); `mtllib`/`usemtl` are ignored (the scene assigns
// the material). Normals and uvs are kept only when every face corner has one, since MeshData stores them
// per vertex. On failure the Error holds the reason only ("No such file or directory", "face 3 refers to
// vertex 9 but the file has 4"); the caller adds the path and the scene location. The file is read
// through `log` (scene/source_log.hpp; may be null).
Expected<MeshData> load_obj_mesh(const std::filesystem::path &path, SourceLog *log);

// Faces as written, without triangulation: the cage of a subdivision surface.
struct PolygonMesh {
  std::vector<Vec3f> positions;
  std::vector<uint32_t> face_sizes;  // vertices per face
  std::vector<uint32_t> indices;     // the faces' vertex indices one after the other
};

// The positions and faces of an OBJ file (normals, uvs and materials ignored), checked as load_obj_mesh
// checks them; faces of fewer than 3 vertices are kept for the caller to report.
Expected<PolygonMesh> load_obj_polygons(const std::filesystem::path &path, SourceLog *log);

}  // namespace nimbus
