#include "scene/mesh_builders.hpp"

#include <cmath>
#include <utility>

namespace nimbus {

namespace {

// Two triangles (0, 1, 2) and (0, 2, 3) over the quad a, b, c, d given counter-clockwise about its normal.
void add_quad(MeshData &mesh, const Vec3f &a, const Vec3f &b, const Vec3f &c, const Vec3f &d) {
  const auto base = uint32_t(mesh.positions.size());
  for (const Vec3f &p : {a, b, c, d}) mesh.positions.push_back(p);
  for (const Vec2f &uv : {Vec2f{0, 0}, Vec2f{1, 0}, Vec2f{1, 1}, Vec2f{0, 1}}) mesh.uvs.push_back(uv);
  for (uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) mesh.indices.push_back(base + i);
}

Vec3f axis(int i) {
  Vec3f e(0.0f);
  e[i] = 1;
  return e;
}

}  // namespace

MeshData rectangle_mesh(float width, float height) {
  MeshData mesh;
  const float x = 0.5f * width, y = 0.5f * height;
  add_quad(mesh, {-x, -y, 0}, {x, -y, 0}, {x, y, 0}, {-x, y, 0});
  return mesh;
}

MeshData box_mesh(const Vec3f &size) {
  MeshData mesh;
  const Vec3f half = 0.5f * size;
  for (int a = 0; a < 3; ++a) {
    for (float sign : {1.0f, -1.0f}) {
      // With (u, v) = the next two axes cyclically, cross(u, v) = +axis a; swapping them gives -axis a,
      // so each face's quad is counter-clockwise seen from outside.
      Vec3f u = axis((a + 1) % 3) * half[(a + 1) % 3], v = axis((a + 2) % 3) * half[(a + 2) % 3];
      if (sign < 0) std::swap(u, v);
      const Vec3f c = axis(a) * (sign * half[a]);
      add_quad(mesh, c - u - v, c + u - v, c + u + v, c - u + v);
    }
  }
  return mesh;
}

void transform_mesh(MeshData &mesh, const Transform &transform) {
  for (Vec3f &p : mesh.positions) p = transform.point(p);
  for (Vec3f &n : mesh.normals) n = normalize(transform.normal(n));
  for (std::vector<Vec3f> &step : mesh.position_steps)
    for (Vec3f &p : step) p = transform.point(p);
  for (std::vector<Vec3f> &step : mesh.normal_steps)
    for (Vec3f &n : step) n = normalize(transform.normal(n));
  if (transform.determinant3() < 0)
    for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3)
      std::swap(mesh.indices[i + 1], mesh.indices[i + 2]);
}

MeshData submesh(const MeshData &mesh, const std::vector<uint32_t> &triangles) {
  MeshData out;
  constexpr uint32_t kUnused = UINT32_MAX;
  std::vector<uint32_t> new_index(mesh.positions.size(), kUnused);
  std::vector<uint32_t> kept;  // the old index of each new vertex
  out.indices.reserve(3 * triangles.size());
  for (uint32_t t : triangles)
    for (size_t c = 3 * size_t(t); c < 3 * size_t(t) + 3; ++c) {
      uint32_t &v = new_index[mesh.indices[c]];
      if (v == kUnused) v = uint32_t(kept.size()), kept.push_back(mesh.indices[c]);
      out.indices.push_back(v);
    }
  const auto pick = [&]<class T>(const std::vector<T> &all) {
    std::vector<T> some;
    if (all.empty()) return some;  // an attribute the mesh does not have
    some.reserve(kept.size());
    for (uint32_t v : kept) some.push_back(all[v]);
    return some;
  };
  out.positions = pick(mesh.positions);
  out.normals = pick(mesh.normals);
  out.uvs = pick(mesh.uvs);
  for (const std::vector<Vec3f> &step : mesh.position_steps) out.position_steps.push_back(pick(step));
  for (const std::vector<Vec3f> &step : mesh.normal_steps) out.normal_steps.push_back(pick(step));
  out.steps_open = mesh.steps_open, out.steps_close = mesh.steps_close;
  return out;
}

std::optional<float> similarity_scale(const Transform &t) {
  const Vec3f c0{t(0, 0), t(1, 0), t(2, 0)}, c1{t(0, 1), t(1, 1), t(2, 1)}, c2{t(0, 2), t(1, 2), t(2, 2)};
  const float s0 = length(c0), s1 = length(c1), s2 = length(c2);
  if (!(s0 > 0)) return std::nullopt;
  // Relative tolerance: the matrix went through float trigonometry and products.
  const float tol = 1e-4f;
  const auto close = [&](float a, float b) { return std::abs(a - b) <= tol * s0; };
  const float s2_tol = tol * s0 * s0;
  if (!close(s0, s1) || !close(s0, s2)) return std::nullopt;
  if (std::abs(dot(c0, c1)) > s2_tol || std::abs(dot(c1, c2)) > s2_tol || std::abs(dot(c0, c2)) > s2_tol)
    return std::nullopt;
  return s0;
}

}  // namespace nimbus
