#include "scene/obj_loader.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <string_view>
#include <tuple>

#include <tiny_obj_loader.h>

#include "core/one_line.hpp"

namespace nimbus {

namespace {

// tinyobjloader's real_t is float or double depending on how the system package was built.
Vec3f vec3_at(const std::vector<tinyobj::real_t> &values, size_t index) {
  return {float(values[3 * index]), float(values[3 * index + 1]), float(values[3 * index + 2])};
}

// tinyobjloader asks for each file an `mtllib` statement names. They are read through the SourceLog and
// parse_mtl instead of its own reader, which drops values it cannot parse and whether a value was written;
// tinyobjloader gets only the name -> index map that `usemtl` needs.
class MtlFiles final : public tinyobj::MaterialReader {
 public:
  MtlFiles(std::filesystem::path dir, SourceLog *log, ObjMaterials &out)
      : dir_(std::move(dir)), log_(log), out_(out) {}

  bool operator()(const std::string &word, std::vector<tinyobj::material_t> *,
                  std::map<std::string, int> *ids, std::string *, std::string *) override {
    // tinyobjloader splits the statement at spaces only, so a tab or a trailing blank stays in a name.
    const size_t first = word.find_first_not_of(" \t\r"), last = word.find_last_not_of(" \t\r");
    if (first == std::string::npos) return false;
    const std::filesystem::path path = (dir_ / word.substr(first, last - first + 1)).lexically_normal();
    if (out_.error.empty() && read_.insert(path).second) read(path, *ids);
    // "Not found" even for a file that was read: tinyobjloader stops at the first file of an `mtllib`
    // statement it is told was found, but every file the statement names belongs to the OBJ.
    return false;
  }

 private:
  void read(const std::filesystem::path &path, std::map<std::string, int> &ids) {
    Expected<std::string> text = read_source_file(path, log_);
    if (!text) {
      out_.error = "'" + path.string() + "': " + text.error().message;
      return;
    }
    Expected<MtlFile> file = parse_mtl(*text, path);
    if (!file) {
      out_.error = file.error().message;
      return;
    }
    for (MtlMaterial &m : file->materials) {
      if (const auto [it, added] = defined_in_.try_emplace(m.name, path.string()); !added) {
        out_.error = "'" + path.string() + "': material '" + shown(m.name) + "' is already defined in '" +
                     it->second + "'";
        return;
      }
      ids.emplace(m.name, int(out_.materials.size()));
      out_.materials.push_back(std::move(m));
    }
    out_.files.push_back({path.string(), std::move(file->ignored)});
  }

  std::filesystem::path dir_;
  SourceLog *log_;
  ObjMaterials &out_;
  std::set<std::filesystem::path> read_;
  std::map<std::string, std::string> defined_in_;  // material name -> the .mtl file that defines it
};

// The names `usemtl` statements give. tinyobjloader turns a name no .mtl file defines into "no material"
// with only a line in its warning text; the scene names them in its own warning instead.
std::set<std::string> usemtl_names(std::string_view text) {
  std::set<std::string> names;
  for (size_t start = 0; start < text.size();) {
    const size_t end = std::min(text.find('\n', start), text.size());
    std::string_view line = text.substr(start, end - start);
    start = end + 1;
    line.remove_prefix(std::min(line.find_first_not_of(" \t"), line.size()));
    if (!line.starts_with("usemtl") || line.size() < 7 || (line[6] != ' ' && line[6] != '\t')) continue;
    line.remove_prefix(7);
    line.remove_prefix(std::min(line.find_first_not_of(" \t"), line.size()));
    // One word, as tinyobjloader reads it.
    if (const std::string_view name = line.substr(0, line.find_first_of(" \t\r")); !name.empty())
      names.emplace(name);
  }
  return names;
}

// The file read and every face corner checked, shared by both readers below.
struct ParsedObj {
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  bool all_normals = true, all_uvs = true;
};

// With `materials` null, `mtllib` and `usemtl` are ignored and no .mtl file is read.
Expected<ParsedObj> parse_obj(const std::filesystem::path &path, SourceLog *log, ObjMaterials *materials) {
  Expected<std::string> text = read_source_file(path, log);
  if (!text) return text.error();
  const std::set<std::string> used = materials ? usemtl_names(*text) : std::set<std::string>();
  std::istringstream in(std::move(text).value());

  ParsedObj obj;
  tinyobj::attrib_t &attrib = obj.attrib;
  std::vector<tinyobj::shape_t> &shapes = obj.shapes;
  std::vector<tinyobj::material_t> unused;
  std::string warn, err;
  std::optional<MtlFiles> mtl_files;
  if (materials) mtl_files.emplace(path.parent_path(), log, *materials);
  // No triangulation by tinyobjloader: it skips quads with bad indices silently and reads vertices before
  // anyone checked them. Faces are checked and triangulated below instead.
  const bool parsed = tinyobj::LoadObj(&attrib, &shapes, &unused, &warn, &err, &in,
                                       mtl_files ? &*mtl_files : nullptr, /*triangulate=*/false,
                                       /*default_vcols_fallback=*/false);
  if (!parsed || !err.empty()) return Error{"malformed OBJ: " + one_line(err.empty() ? warn : err)};
  if (materials && materials->error.empty() && !materials->materials.empty())
    for (const std::string &name : used)
      if (std::none_of(materials->materials.begin(), materials->materials.end(),
                       [&](const MtlMaterial &m) { return m.name == name; }))
        materials->unknown.push_back(name);

  const auto num_positions = int(attrib.vertices.size() / 3);
  const auto num_normals = int(attrib.normals.size() / 3);
  const auto num_uvs = int(attrib.texcoords.size() / 2);
  for (int i = 0; i < num_positions; ++i)
    if (!is_finite(vec3_at(attrib.vertices, size_t(i))))
      return Error{"vertex " + std::to_string(i + 1) + " is not a finite single-precision number"};

  // Validate every face corner and decide whether normals and uvs can be used.
  size_t face_number = 0, triangles = 0;
  for (const tinyobj::shape_t &shape : shapes) {
    size_t corner = 0;
    for (unsigned char n : shape.mesh.num_face_vertices) {
      ++face_number;
      for (size_t c = corner; c < corner + n; ++c) {
        const tinyobj::index_t &idx = shape.mesh.indices[c];
        if (idx.vertex_index < 0 || idx.vertex_index >= num_positions)
          return Error{"face " + std::to_string(face_number) + " refers to vertex " +
                       std::to_string(idx.vertex_index + 1) + " but the file has " +
                       std::to_string(num_positions)};
        if (idx.normal_index < -1 || idx.normal_index >= num_normals)
          return Error{"face " + std::to_string(face_number) + " refers to normal " +
                       std::to_string(idx.normal_index + 1) + " but the file has " +
                       std::to_string(num_normals)};
        if (idx.texcoord_index < -1 || idx.texcoord_index >= num_uvs)
          return Error{"face " + std::to_string(face_number) + " refers to texture coordinate " +
                       std::to_string(idx.texcoord_index + 1) + " but the file has " +
                       std::to_string(num_uvs)};
        obj.all_normals &= idx.normal_index >= 0;
        obj.all_uvs &= idx.texcoord_index >= 0;
      }
      if (n >= 3) triangles += n - 2;
      corner += n;
    }
  }
  if (triangles == 0) return Error{"the file has no faces"};
  return obj;
}

}  // namespace

Expected<ObjMesh> load_obj_mesh(const std::filesystem::path &path, SourceLog *log) {
  ObjMesh out;
  Expected<ParsedObj> parsed = parse_obj(path, log, &out.materials);
  if (!parsed) return parsed.error();
  const tinyobj::attrib_t &attrib = parsed->attrib;
  const std::vector<tinyobj::shape_t> &shapes = parsed->shapes;
  const bool all_normals = parsed->all_normals, all_uvs = parsed->all_uvs;

  // OBJ indexes positions, normals and uvs separately; MeshData shares one index, so each distinct
  // (position, normal, uv) corner becomes one vertex.
  MeshData &mesh = out.mesh;
  std::map<std::tuple<int, int, int>, uint32_t> vertex_of;
  const auto vertex = [&](const tinyobj::index_t &idx) -> Expected<uint32_t> {
    const int vn = all_normals ? idx.normal_index : -1, vt = all_uvs ? idx.texcoord_index : -1;
    const auto [it, inserted] =
        vertex_of.try_emplace({idx.vertex_index, vn, vt}, uint32_t(mesh.positions.size()));
    if (inserted) {
      mesh.positions.push_back(vec3_at(attrib.vertices, size_t(idx.vertex_index)));
      if (vn >= 0) {
        const Vec3f n = vec3_at(attrib.normals, size_t(vn));
        if (!is_finite(n) || !(length(n) > 0))
          return Error{"normal " + std::to_string(vn + 1) + " is zero or not finite"};
        mesh.normals.push_back(normalize(n));
      }
      if (vt >= 0)
        mesh.uvs.push_back(
            {float(attrib.texcoords[2 * size_t(vt)]), float(attrib.texcoords[2 * size_t(vt) + 1])});
    }
    return it->second;
  };
  std::map<int, size_t> part_of;  // material -> index in out.parts
  for (const tinyobj::shape_t &shape : shapes) {
    size_t corner = 0;
    for (size_t face = 0; face < shape.mesh.num_face_vertices.size(); ++face) {
      const unsigned char n = shape.mesh.num_face_vertices[face];
      if (n >= 3) {
        const int material = face < shape.mesh.material_ids.size() ? shape.mesh.material_ids[face] : -1;
        const auto [it, added] = part_of.try_emplace(material, out.parts.size());
        if (added) out.parts.push_back({material, {}});
        std::vector<uint32_t> &triangles = out.parts[it->second].triangles;
        for (size_t k = 1; k + 1 < n; ++k) {
          triangles.push_back(uint32_t(mesh.indices.size() / 3));
          for (size_t c : {corner, corner + k, corner + k + 1}) {
            Expected<uint32_t> v = vertex(shape.mesh.indices[c]);
            if (!v) return v.error();
            mesh.indices.push_back(*v);
          }
        }
      }
      corner += n;
    }
  }
  return out;
}

Expected<PolygonMesh> load_obj_polygons(const std::filesystem::path &path, SourceLog *log) {
  Expected<ParsedObj> parsed = parse_obj(path, log, nullptr);
  if (!parsed) return parsed.error();
  PolygonMesh out;
  const std::vector<tinyobj::real_t> &v = parsed->attrib.vertices;
  for (size_t i = 0; i < v.size() / 3; ++i) out.positions.push_back(vec3_at(v, i));
  for (const tinyobj::shape_t &shape : parsed->shapes) {
    size_t corner = 0;
    for (unsigned char n : shape.mesh.num_face_vertices) {
      out.face_sizes.push_back(n);
      for (size_t c = corner; c < corner + n; ++c)
        out.indices.push_back(uint32_t(shape.mesh.indices[c].vertex_index));
      corner += n;
    }
  }
  return out;
}

}  // namespace nimbus
