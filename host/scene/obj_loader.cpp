#include "scene/obj_loader.hpp"

#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <tuple>

#include <tiny_obj_loader.h>

#include "core/one_line.hpp"

namespace nimbus {

namespace {

// tinyobjloader's real_t is float or double depending on how the system package was built.
Vec3f vec3_at(const std::vector<tinyobj::real_t> &values, size_t index) {
  return {float(values[3 * index]), float(values[3 * index + 1]), float(values[3 * index + 2])};
}

// The file read and every face corner checked, shared by both readers below.
struct ParsedObj {
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  bool all_normals = true, all_uvs = true;
};

Expected<ParsedObj> parse_obj(const std::filesystem::path &path, SourceLog *log) {
  Expected<std::string> text = read_source_file(path, log);
  if (!text) return text.error();
  std::istringstream in(std::move(text).value());

  ParsedObj obj;
  tinyobj::attrib_t &attrib = obj.attrib;
  std::vector<tinyobj::shape_t> &shapes = obj.shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warn, err;
  // No triangulation by tinyobjloader: it skips quads with bad indices silently and reads vertices before
  // anyone checked them. Faces are checked and triangulated below instead.
  const bool parsed = tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, &in,
                                       /*readMatFn=*/nullptr, /*triangulate=*/false,
                                       /*default_vcols_fallback=*/false);
  if (!parsed || !err.empty()) return Error{"malformed OBJ: " + one_line(err.empty() ? warn : err)};

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

Expected<MeshData> load_obj_mesh(const std::filesystem::path &path, SourceLog *log) {
  Expected<ParsedObj> parsed = parse_obj(path, log);
  if (!parsed) return parsed.error();
  const tinyobj::attrib_t &attrib = parsed->attrib;
  const std::vector<tinyobj::shape_t> &shapes = parsed->shapes;
  const bool all_normals = parsed->all_normals, all_uvs = parsed->all_uvs;

  // OBJ indexes positions, normals and uvs separately; MeshData shares one index, so each distinct
  // (position, normal, uv) corner becomes one vertex.
  MeshData mesh;
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
  for (const tinyobj::shape_t &shape : shapes) {
    size_t corner = 0;
    for (unsigned char n : shape.mesh.num_face_vertices) {
      for (size_t k = 1; k + 1 < n; ++k) {
        for (size_t c : {corner, corner + k, corner + k + 1}) {
          Expected<uint32_t> v = vertex(shape.mesh.indices[c]);
          if (!v) return v.error();
          mesh.indices.push_back(*v);
        }
      }
      corner += n;
    }
  }
  return mesh;
}

Expected<PolygonMesh> load_obj_polygons(const std::filesystem::path &path, SourceLog *log) {
  Expected<ParsedObj> parsed = parse_obj(path, log);
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
