#include "scene/subdivision.hpp"

#include <opensubdiv/far/error.h>
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

namespace nimbus {

namespace {

namespace osd = OpenSubdiv::OPENSUBDIV_VERSION;

// OpenSubdiv reports topology problems through process-wide callbacks that print by default; they are
// collected instead, so that they reach the user as the scene's error. Parsing is single-threaded per
// scene, and thread_local keeps concurrent parses apart.
thread_local std::string osd_errors;

void collect_error(osd::Far::ErrorType, const char *message) {
  if (osd_errors.empty()) osd_errors = message;
}
void ignore_warning(const char *) {}  // e.g. non-manifold edges, which OpenSubdiv handles

// The primvar type OpenSubdiv interpolates: weighted sums of positions.
struct Point {
  float x = 0, y = 0, z = 0;
  void Clear(void * = nullptr) { x = y = z = 0; }
  void AddWithWeight(const Point &p, float w) {
    x += w * p.x;
    y += w * p.y;
    z += w * p.z;
  }
  Vec3f vec() const { return {x, y, z}; }
};

// Area-weighted vertex normals of a triangle mesh (zero where a vertex has no area around it).
std::vector<Vec3f> face_normals_at_vertices(const MeshData &mesh) {
  std::vector<Vec3f> n(mesh.positions.size(), Vec3f(0.0f));
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
    const Vec3f fn = cross(mesh.positions[b] - mesh.positions[a], mesh.positions[c] - mesh.positions[a]);
    for (uint32_t v : {a, b, c}) n[v] = n[v] + fn;
  }
  return n;
}

// Triangles of the finest level's faces: quads split along one diagonal, other polygons fanned.
void triangulate(const osd::Far::TopologyLevel &level, MeshData &mesh) {
  for (int f = 0; f < level.GetNumFaces(); ++f) {
    const osd::Far::ConstIndexArray v = level.GetFaceVertices(f);
    for (int k = 1; k + 1 < v.size(); ++k)
      for (int i : {0, k, k + 1}) mesh.indices.push_back(uint32_t(v[i]));
  }
}

bool all_quads(const SubdivisionCage &cage) {
  return std::all_of(cage.face_sizes.begin(), cage.face_sizes.end(), [](uint32_t n) { return n == 4; });
}

}  // namespace

uint64_t subdivision_triangle_count(const SubdivisionCage &cage, SubdivisionScheme scheme, int level) {
  uint64_t corners = 0, fan = 0;
  for (uint32_t n : cage.face_sizes) {
    corners += n;
    fan += n - 2;
  }
  if (scheme == SubdivisionScheme::Loop) return fan << (2 * level);
  if (level == 0) return fan;
  return 2 * (corners << (2 * (level - 1)));
}

Expected<MeshData> subdivide(const SubdivisionCage &cage, SubdivisionScheme scheme, int level) {
  using Descriptor = osd::Far::TopologyDescriptor;
  using Factory = osd::Far::TopologyRefinerFactory<Descriptor>;

  std::vector<int> sizes(cage.face_sizes.begin(), cage.face_sizes.end());
  std::vector<osd::Far::Index> indices(cage.indices.begin(), cage.indices.end());
  std::vector<osd::Far::Index> crease_pairs;
  std::vector<float> crease_weights;
  for (const SubdivisionCage::Crease &c : cage.creases) {
    crease_pairs.insert(crease_pairs.end(), {osd::Far::Index(c.v0), osd::Far::Index(c.v1)});
    crease_weights.push_back(c.sharpness);
  }
  Descriptor desc;
  desc.numVertices = int(cage.positions.size());
  desc.numFaces = int(sizes.size());
  desc.numVertsPerFace = sizes.data();
  desc.vertIndicesPerFace = indices.data();
  desc.numCreases = int(crease_weights.size());
  desc.creaseVertexIndexPairs = crease_pairs.data();
  desc.creaseWeights = crease_weights.data();

  osd::Sdc::Options options;
  options.SetVtxBoundaryInterpolation(osd::Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER);
  const osd::Sdc::SchemeType type =
      scheme == SubdivisionScheme::Loop ? osd::Sdc::SCHEME_LOOP : osd::Sdc::SCHEME_CATMARK;

  osd_errors.clear();
  osd::Far::SetErrorCallback(collect_error);
  osd::Far::SetWarningCallback(ignore_warning);
  std::unique_ptr<osd::Far::TopologyRefiner> refiner(Factory::Create(desc, Factory::Options(type, options)));
  if (!refiner || !osd_errors.empty())
    return Error{"OpenSubdiv rejects the cage: " +
                 (osd_errors.empty() ? std::string("invalid topology") : osd_errors)};
  if (level > 0) {
    osd::Far::TopologyRefiner::UniformOptions uniform(level);
    uniform.fullTopologyInLastLevel = true;  // Limit() needs the finest level's edges
    refiner->RefineUniform(uniform);
  }

  // Interpolate level by level through one buffer holding every level's vertices.
  std::vector<Point> points(size_t(refiner->GetNumVerticesTotal()));
  for (size_t i = 0; i < cage.positions.size(); ++i)
    points[i] = {cage.positions[i].x, cage.positions[i].y, cage.positions[i].z};
  osd::Far::PrimvarRefiner primvars(*refiner);
  Point *src = points.data();
  for (int l = 1; l <= level; ++l) {
    Point *dst = src + refiner->GetLevel(l - 1).GetNumVertices();
    primvars.Interpolate(l, src, dst);
    src = dst;
  }

  const osd::Far::TopologyLevel &finest = refiner->GetLevel(level);
  const auto count = size_t(finest.GetNumVertices());
  MeshData mesh;
  triangulate(finest, mesh);
  const bool limit = scheme == SubdivisionScheme::Loop || level > 0 || all_quads(cage);
  std::vector<Point> position(count), du(count), dv(count);
  if (limit) {
    primvars.Limit(src, position, du, dv);
  } else {
    std::copy(src, src + count, position.begin());
  }
  if (!osd_errors.empty()) return Error{"OpenSubdiv: " + osd_errors};
  for (const Point &p : position) mesh.positions.push_back(p.vec());

  // Limit normals where the tangents define one, oriented like the faces around the vertex (whose
  // winding is the cage's); the faces' own normals where they do not (e.g. degenerate tangents).
  const std::vector<Vec3f> around = face_normals_at_vertices(mesh);
  mesh.normals.resize(count);
  for (size_t i = 0; i < count; ++i) {
    Vec3f n = limit ? cross(du[i].vec(), dv[i].vec()) : Vec3f(0.0f);
    const float len = length(n);
    if (!(len > 0) || !std::isfinite(len)) n = around[i];
    if (dot(n, around[i]) < 0) n = -n;
    mesh.normals[i] = length(n) > 0 ? normalize(n) : Vec3f(0, 0, 1);
  }
  return mesh;
}

int auto_subdivision_level(const SubdivisionCage &cage, const Transform &to_world, const CameraDesc &camera,
                           uint32_t width) {
  const double focal = double(width) / (2 * std::tan(double(radians(camera.fov_degrees)) / 2));
  std::vector<Vec3f> world(cage.positions.size());
  for (size_t i = 0; i < world.size(); ++i) world[i] = to_world.point(cage.positions[i]);
  double longest = 0;
  size_t start = 0;
  for (uint32_t n : cage.face_sizes) {
    for (uint32_t k = 0; k < n; ++k) {
      const Vec3f a = world[cage.indices[start + k]], b = world[cage.indices[start + (k + 1) % n]];
      // Closest point of the edge to the camera.
      const Vec3f ab = b - a;
      const float ab2 = dot(ab, ab);
      const float t = ab2 > 0 ? std::clamp(dot(camera.position - a, ab) / ab2, 0.0f, 1.0f) : 0.0f;
      const double d = double(length(a + ab * t - camera.position));
      // An edge through the eye projects to any size: the finest level.
      const double pixels = d > 0 ? double(std::sqrt(ab2)) * focal / d : HUGE_VAL;
      longest = std::max(longest, pixels);
    }
    start += n;
  }
  if (!(longest > 1)) return 0;
  const double level = std::ceil(std::log2(longest));
  return int(std::min(level, double(kMaxSubdivisionLevel)));
}

}  // namespace nimbus
