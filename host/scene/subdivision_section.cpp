// `shape: subdivision` — a polygon cage (an OBJ file, or inline `positions` and `faces`) refined once at
// load time into triangles (subdivision.hpp has the geometry). The cage is checked here so that every
// problem names its key; OpenSubdiv then only sees valid input.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>
#include <string>
#include <utility>

#include "scene/obj_loader.hpp"
#include "scene/sections.hpp"
#include "scene/subdivision.hpp"

namespace nimbus::scene_yaml {

namespace {

SubdivisionCage read_cage_file(const YamlMap &m, const YamlValue &file) {
  for (const char *other : {"positions", "faces"})
    if (m.has(other)) m.key(other).fail("cannot be combined with 'file'");
  const std::filesystem::path path = file.source().resolve(file.nonempty_string());
  Expected<PolygonMesh> obj = load_obj_polygons(path, file.source().log);
  if (!obj) file.fail("cannot load cage '" + path.string() + "': " + obj.error().message);
  SubdivisionCage cage;
  cage.positions = std::move(obj->positions);
  cage.face_sizes = std::move(obj->face_sizes);
  cage.indices = std::move(obj->indices);
  size_t start = 0;
  for (size_t f = 0; f < cage.face_sizes.size(); ++f) {
    const uint32_t n = cage.face_sizes[f];
    std::set<uint32_t> distinct(cage.indices.begin() + long(start), cage.indices.begin() + long(start + n));
    if (n < 3 || distinct.size() != n)
      file.fail("cannot use cage '" + path.string() + "': face " + std::to_string(f + 1) +
                " needs at least 3 distinct vertices");
    start += n;
  }
  return cage;
}

// `faces: [[i, j, k, l], ...]`: polygons of at least 3 distinct vertices, counter-clockwise seen from the
// outside.
SubdivisionCage read_inline_cage(const YamlMap &m) {
  if (!m.has("positions") && !m.has("faces"))
    m.self().fail("a subdivision surface needs 'file', or 'positions' and 'faces'");
  SubdivisionCage cage;
  for (const YamlValue &p : m.require("positions").sequence()) cage.positions.push_back(p.vec3());
  const YamlValue faces = m.require("faces");
  const std::vector<YamlValue> items = faces.sequence();
  if (items.empty()) faces.fail("a subdivision surface needs at least one face");
  for (const YamlValue &face : items) {
    if (!face.is_sequence()) face.fail("expected a face [i, j, k, ...], got " + face.describe());
    const std::vector<YamlValue> corners = face.sequence();
    if (corners.size() < 3)
      face.fail("a face needs at least 3 vertices, got " + std::to_string(corners.size()));
    std::set<uint32_t> seen;
    for (const YamlValue &c : corners) {
      const int64_t index = c.integer(Range::at_least(0));
      if (index >= int64_t(cage.positions.size()))
        c.fail("vertex index " + c.shown() + " is out of range: the cage has " +
               std::to_string(cage.positions.size()) + " positions");
      if (!seen.insert(uint32_t(index)).second) c.fail("vertex " + c.shown() + " appears twice in the face");
      cage.indices.push_back(uint32_t(index));
    }
    cage.face_sizes.push_back(uint32_t(corners.size()));
  }
  return cage;
}

// `creases: [[v0, v1, sharpness], ...]` on edges of the cage; sharpness 0 (smooth) to 10 (infinitely sharp).
void read_creases(const YamlValue &v, SubdivisionCage &cage) {
  std::set<std::pair<uint32_t, uint32_t>> edges;
  size_t start = 0;
  for (uint32_t n : cage.face_sizes) {
    for (uint32_t k = 0; k < n; ++k) {
      const uint32_t a = cage.indices[start + k], b = cage.indices[start + (k + 1) % n];
      edges.emplace(std::min(a, b), std::max(a, b));
    }
    start += n;
  }
  for (const YamlValue &crease : v.sequence()) {
    const std::vector<YamlValue> c = crease.sequence_of(3, "[v0, v1, sharpness]");
    const auto v0 = uint32_t(c[0].integer(Range::at_least(0))),
               v1 = uint32_t(c[1].integer(Range::at_least(0)));
    const float sharpness = c[2].real(Range::closed(0, double(kInfinitelySharp)));
    if (!edges.count({std::min(v0, v1), std::max(v0, v1)}))
      crease.fail("vertices " + c[0].shown() + " and " + c[1].shown() + " are not the ends of a cage edge");
    cage.creases.push_back({v0, v1, sharpness});
  }
}

SubdivisionScheme read_scheme(const YamlValue &v, const SubdivisionCage &cage) {
  const std::string name = v.string();
  if (name == "catmull-clark") return SubdivisionScheme::CatmullClark;
  if (name != "loop")
    v.fail("unknown subdivision scheme '" + abbreviate(name) + "'; known: catmull-clark, loop");
  for (size_t f = 0; f < cage.face_sizes.size(); ++f)
    if (cage.face_sizes[f] != 3)
      v.fail("loop subdivides triangles only, but face " + std::to_string(f) + " of the cage has " +
             std::to_string(cage.face_sizes[f]) + " vertices; use catmull-clark");
  return SubdivisionScheme::Loop;
}

}  // namespace

MeshData read_subdivision(const YamlMap &m, const Transform &to_world, const CameraDesc &camera,
                          const RenderDesc &render) {
  const std::optional<YamlValue> file = m.get("file");
  SubdivisionCage cage = file ? read_cage_file(m, *file) : read_inline_cage(m);
  if (auto v = m.get("creases")) read_creases(*v, cage);
  const std::optional<YamlValue> scheme_value = m.get("scheme");
  const SubdivisionScheme scheme =
      scheme_value ? read_scheme(*scheme_value, cage) : SubdivisionScheme::CatmullClark;

  int level = 0;
  const std::optional<YamlValue> level_value = m.get("level");
  if (level_value && !(level_value->is_scalar() && level_value->text() == "auto")) {
    const std::string &text = level_value->text();
    const bool numeric = !text.empty() && (std::isdigit(static_cast<unsigned char>(text[0])) ||
                                           text[0] == '-' || text[0] == '+' || text[0] == '.');
    if (!numeric)
      level_value->fail("expected an integer in [0, " + std::to_string(kMaxSubdivisionLevel) +
                        "] or auto, got " + level_value->describe());
    level = int(level_value->integer(Range::closed(0, kMaxSubdivisionLevel)));
    const uint64_t triangles = subdivision_triangle_count(cage, scheme, level);
    if (triangles > kMaxSubdivisionTriangles)
      level_value->fail("level " + std::to_string(level) + " would make " + std::to_string(triangles) +
                        " triangles (at most " + std::to_string(kMaxSubdivisionTriangles) + ")");
  } else {
    // Auto: fine enough for the camera, but never beyond the triangle budget.
    level = auto_subdivision_level(cage, to_world, camera, render.width);
    while (level > 0 && subdivision_triangle_count(cage, scheme, level) > kMaxSubdivisionTriangles) --level;
  }

  Expected<MeshData> mesh = subdivide(cage, scheme, level);
  if (!mesh) (file ? *file : m.self()).fail(mesh.error().message);
  return std::move(mesh).value();
}

}  // namespace nimbus::scene_yaml
