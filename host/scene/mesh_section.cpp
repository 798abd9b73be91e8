// `shape: mesh` and `meshes:` entries — triangles written inline (positions, indices, optional normals and
// uvs) or read from an OBJ or glTF file named relative to the scene file.
#include <cmath>
#include <string>

#include "scene/sections.hpp"

namespace nimbus::scene_yaml {

namespace {

std::shared_ptr<const LoadedMesh> read_mesh_file(const YamlMap &m, const YamlValue &file,
                                                 MeshLibrary &library) {
  for (const char *other : {"positions", "indices", "normals", "uvs"})
    if (m.has(other)) m.key(other).fail("cannot be combined with 'file'");
  return library.load(file);
}

// Indices as a flat list [i, j, k, ...] or as triangles [[i, j, k], ...]; every one must name a position.
std::vector<uint32_t> read_indices(const YamlValue &v, size_t num_positions) {
  std::vector<YamlValue> items = v.sequence();
  if (items.empty()) v.fail("a mesh needs at least one triangle");
  std::vector<YamlValue> flat;
  if (items.front().is_sequence()) {
    for (const YamlValue &triangle : items)
      for (YamlValue &i : triangle.sequence_of(3, "a triangle [i, j, k]")) flat.push_back(std::move(i));
  } else {
    if (items.size() % 3 != 0)
      v.fail("expected 3 indices per triangle, got " + std::to_string(items.size()) + " indices");
    flat = std::move(items);
  }
  std::vector<uint32_t> out;
  out.reserve(flat.size());
  for (const YamlValue &i : flat) {
    const int64_t index = i.integer(Range::at_least(0));
    if (index >= int64_t(num_positions))
      i.fail("vertex index " + i.shown() + " is out of range: the mesh has " + std::to_string(num_positions) +
             " positions");
    out.push_back(uint32_t(index));
  }
  return out;
}

// Per-vertex attributes must line up with the positions one to one.
std::vector<YamlValue> per_vertex(const YamlValue &v, size_t num_positions, std::string_view what) {
  std::vector<YamlValue> items = v.sequence();
  if (items.size() != num_positions)
    v.fail("has " + std::to_string(items.size()) + " " + std::string(what) + " but the mesh has " +
           std::to_string(num_positions) + " positions");
  return items;
}

}  // namespace

std::shared_ptr<const LoadedMesh> read_mesh(const YamlMap &m, MeshLibrary &library) {
  if (auto file = m.get("file")) return read_mesh_file(m, *file, library);
  if (!m.has("positions") && !m.has("indices"))
    m.self().fail("a mesh needs 'file', or 'positions' and 'indices'");

  auto loaded = std::make_shared<LoadedMesh>();
  MeshData &mesh = loaded->mesh;
  for (const YamlValue &p : m.require("positions").sequence()) mesh.positions.push_back(p.vec3());
  mesh.indices = read_indices(m.require("indices"), mesh.positions.size());
  if (auto normals = m.get("normals")) {
    for (const YamlValue &n : per_vertex(*normals, mesh.positions.size(), "normals")) {
      const Vec3f normal = n.vec3();
      if (!(length(normal) > 0)) n.fail("a normal must not be the zero vector");
      mesh.normals.push_back(normalize(normal));
    }
  }
  if (auto uvs = m.get("uvs"))
    for (const YamlValue &uv : per_vertex(*uvs, mesh.positions.size(), "uvs")) mesh.uvs.push_back(uv.vec2());
  return loaded;
}

void read_meshes(const YamlValue &section, MeshLibrary &library) {
  if (section.is_null()) return;
  const YamlMap meshes = section.map();
  for (const YamlMap::Entry &e : meshes.entries()) {
    if (e.key.empty()) e.key_value.fail("mesh names must not be empty");
    const YamlMap m = e.value.map({"file", "positions", "indices", "normals", "uvs"});
    library.add(e.key, read_mesh(m, library), e.key_value);
  }
}

}  // namespace nimbus::scene_yaml
