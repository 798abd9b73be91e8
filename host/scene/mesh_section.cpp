// `shape: mesh` — triangles written inline (positions, indices, optional normals and uvs) or read from an
// OBJ file named relative to the scene file.
#include <cmath>
#include <string>

#include "scene/obj_loader.hpp"
#include "scene/sections.hpp"

namespace nimbus::scene_yaml {

namespace {

MeshData read_mesh_file(const YamlMap &m, const YamlValue &file) {
  for (const char *other : {"positions", "indices", "normals", "uvs"})
    if (m.has(other)) m.key(other).fail("cannot be combined with 'file'");
  const std::filesystem::path path = file.source().resolve(file.nonempty_string());
  Expected<MeshData> mesh = load_obj_mesh(path);
  if (!mesh) file.fail("cannot load mesh '" + path.string() + "': " + mesh.error().message);
  return std::move(mesh).value();
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

MeshData read_mesh(const YamlMap &m) {
  if (auto file = m.get("file")) return read_mesh_file(m, *file);
  if (!m.has("positions") && !m.has("indices"))
    m.self().fail("a mesh needs 'file', or 'positions' and 'indices'");

  MeshData mesh;
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
  return mesh;
}

}  // namespace nimbus::scene_yaml
