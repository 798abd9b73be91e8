// Wavefront OBJ files as one triangle mesh, through tinyobjloader, with the .mtl materials of its faces.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/expected.hpp"
#include "scene/mtl_reader.hpp"
#include "scene/scene_desc.hpp"
#include "scene/source_log.hpp"

namespace nimbus {

// The materials of the .mtl files an OBJ file names (`mtllib`), as written; the scene maps them to its own
// (scene/obj_material.cpp).
struct ObjMaterials {
  std::vector<MtlMaterial> materials;  // of every .mtl file, in the order `mtllib` names them; names unique
  struct File {
    std::string path;                  // resolved against the OBJ file's directory
    std::vector<std::string> ignored;  // MtlFile::ignored
  };
  std::vector<File> files;
  std::vector<std::string> unknown;  // names `usemtl` gives that no .mtl file defines
  // Why the materials cannot be used: a .mtl file that cannot be read ("'PATH': No such file or
  // directory") or is malformed (parse_mtl's error), or a name two files define; empty when all is well.
  // Kept rather than failing the mesh: an object that assigns its own material needs none of them.
  std::string error;
};

// The faces that use one material, as triangles of the mesh (index i: MeshData::indices[3i .. 3i + 2]).
struct ObjPart {
  int material = -1;  // index in ObjMaterials::materials; -1: faces without a `usemtl` naming a material
  std::vector<uint32_t> triangles;
};

struct ObjMesh {
  MeshData mesh;
  std::vector<ObjPart> parts;  // every triangle in one part, parts in the order their material first appears
  ObjMaterials materials;
};

// All groups and objects of the file merged into one mesh, in the file's coordinates and order; polygons
// are fan-triangulated (OBJ faces are expected to be convex). Normals and uvs are kept only when every
// face corner has one, since MeshData stores them per vertex. On failure the Error holds the reason only
// ("No such file or directory", "face 3 refers to vertex 9 but the file has 4"); the caller adds the path
// and the scene location. The file and its .mtl files are read through `log` (scene/source_log.hpp; may
// be null); .mtl files that cannot be used leave ObjMaterials::error, not a failure.
Expected<ObjMesh> load_obj_mesh(const std::filesystem::path &path, SourceLog *log);

// Faces as written, without triangulation: the cage of a subdivision surface.
struct PolygonMesh {
  std::vector<Vec3f> positions;
  std::vector<uint32_t> face_sizes;  // vertices per face
  std::vector<uint32_t> indices;     // the faces' vertex indices one after the other
};

// The positions and faces of an OBJ file (normals, uvs and materials ignored: no .mtl file is read),
// checked as load_obj_mesh checks them; faces of fewer than 3 vertices are kept for the caller to report.
Expected<PolygonMesh> load_obj_polygons(const std::filesystem::path &path, SourceLog *log);

}  // namespace nimbus
