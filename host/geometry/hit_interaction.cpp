// GeometryScene::interaction: the surface record of a ray hit. Each shape computes its surface where it is
// defined (a moving one in object space at the ray's time), a moving shape's is carried to world space,
// and one function writes the record. A static triangle, nearly every hit of a production scene, takes a
// path of its own without the motion and analytic-shape branches (1.2 % fewer instructions per sample).
#include <cmath>
#include <optional>

#include "geometry/geometry_scene.hpp"

namespace nimbus {
namespace {

// A hit's surface before the record is written; error bounds each coordinate's rounding error in p. The
// functions that fill and write it are forced inline: called, they pass it through memory, which costs
// more than the split saves.
struct Surface {
  Vec3f p, error, ng, ns, dpdu, dpdv;
  Vec2f uv;
};

// Triangle prim's corner indices and rest positions (and vertex normals, when the mesh has them).
struct Corners {
  uint32_t i[3];
  Vec3f v[3], n[3];
  Corners(const MeshData &m, uint32_t prim)
      : i{m.indices[3 * prim], m.indices[3 * prim + 1], m.indices[3 * prim + 2]},
        v{m.positions[i[0]], m.positions[i[1]], m.positions[i[2]]} {
    if (!m.normals.empty()) n[0] = m.normals[i[0]], n[1] = m.normals[i[1]], n[2] = m.normals[i[2]];
  }
};

// The hit at barycentrics (b1, b2) of the triangle with corners c of mesh m: its rest positions, or a
// deforming mesh's at the ray's time.
[[gnu::always_inline]] inline Surface triangle_surface(const MeshData &m, const Corners &c, float b1,
                                                       float b2) {
  const Vec3f(&v)[3] = c.v;
  const Vec3f *n = m.normals.empty() ? nullptr : c.n;
  const uint32_t i0 = c.i[0], i1 = c.i[1], i2 = c.i[2];
  Surface s;
  const float b0 = 1 - b1 - b2;
  // Barycentric interpolation is far more accurate than o + t d (pbrt-v4 section 6.8).
  s.p = v[0] * b0 + v[1] * b1 + v[2] * b2;
  s.error = triangle_point_error(v[0], v[1], v[2], b0, b1, b2);
  // Far from the origin a point within an ulp of an edge can round onto the plane of the neighbouring
  // face, where a new ray would meet that face at t = 0 from its far side (a leak at box corners).
  // Nudging the point a few ulps towards the triangle's centroid, within its plane, keeps it strictly
  // inside its own triangle and off every neighbour's plane.
  const Vec3f to_centroid = (v[0] + v[1] + v[2]) * (1.0f / 3) - s.p;
  if (const float dist = length(to_centroid); dist > 0) {
    const float nudge = std::min(max_component(abs(s.p)) * 0x1p-21f, 0.5f * dist);
    s.p += to_centroid * (nudge / dist);
    s.error += abs(s.p) * rounding_gamma(3);
  }
  const Vec3f e1 = v[1] - v[0], e2 = v[2] - v[0];
  s.ng = oriented_triangle_normal(v[0], v[1], v[2], n, b1, b2);
  Vec2f uv0{0, 0}, uv1{1, 0}, uv2{1, 1};
  if (!m.uvs.empty()) uv0 = m.uvs[i0], uv1 = m.uvs[i1], uv2 = m.uvs[i2];
  s.uv = {uv0.x * b0 + uv1.x * b1 + uv2.x * b2, uv0.y * b0 + uv1.y * b1 + uv2.y * b2};
  if (m.uvs.empty()) {
    // The general solve below with these default uvs (det = 1), without its division.
    s.dpdu = e1, s.dpdv = e2 - e1;
  } else {
    const float du1 = uv1.x - uv0.x, du2 = uv2.x - uv0.x, dv1 = uv1.y - uv0.y, dv2 = uv2.y - uv0.y;
    const float det = du1 * dv2 - dv1 * du2;
    if (std::abs(det) > 1e-12f) {
      s.dpdu = (e1 * dv2 - e2 * dv1) / det;
      s.dpdv = (e2 * du1 - e1 * du2) / det;
    } else {
      const Frame f = Frame::from_normal(s.ng);
      s.dpdu = f.s, s.dpdv = f.t;
    }
  }
  s.ns = s.ng;
  if (n) {
    const Vec3f shading = n[0] * b0 + n[1] * b1 + n[2] * b2;
    if (length_squared(shading) > 0) s.ns = normalize(shading);
  }
  return s;
}

// The hit on a sphere, re-projected onto it: removes the error of o + t d along the ray.
Surface sphere_surface(const ShapeRecord &sh, const Vec3f &org, const Vec3f &dir, float t) {
  Surface s;
  const Vec3f d = org + dir * t - sh.center;
  s.ng = normalize(d);
  s.p = sh.center + s.ng * sh.radius;
  s.ns = s.ng;
  s.error = sphere_point_error(sh.center, s.ng, sh.radius);
  const float phi = std::atan2(s.ng.y, s.ng.x), theta = std::acos(clamp(s.ng.z, -1, 1));
  s.uv = {(phi < 0 ? phi + 2 * kPi : phi) / (2 * kPi), theta / kPi};
  s.dpdu = Vec3f{-s.ng.y, s.ng.x, 0} * (2 * kPi * sh.radius);
  if (length_squared(s.dpdu) == 0) s.dpdu = Frame::from_normal(s.ng).s;
  s.dpdv = cross(s.ng, s.dpdu);
  return s;
}

// The hit on a disk, projected onto its plane.
Surface disk_surface(const ShapeRecord &sh, const Vec3f &org, const Vec3f &dir, float t) {
  Surface s;
  s.p = org + dir * t;
  s.p -= sh.normal * dot(s.p - sh.center, sh.normal);
  s.ng = s.ns = sh.normal;
  const Frame f = Frame::from_normal(sh.normal);
  const Vec3f l = f.to_local(s.p - sh.center);
  s.uv = {0.5f + 0.5f * l.x / sh.radius, 0.5f + 0.5f * l.y / sh.radius};
  s.dpdu = f.s, s.dpdv = f.t;
  s.error = disk_point_error(s.p, sh.center);
  return s;
}

// Relative difference between the surface Embree intersects in a moving instance and the one its
// interpolated transform gives, allowed for in the offset distance.
constexpr float kInstanceMismatch = 0x1p-18f;

// An object-space surface carried to world space by a moving shape's transform at the ray's time
// (to_world, and its inverse to_object); the transform's own rounding joins the error bound.
Surface moved(const Surface &o, const Transform &m, const Transform &inv) {
  Surface s = o;
  for (int r = 0; r < 3; ++r) {  // pbrt-v4 6.8.6: the carried error through |M|, plus the product's own
    float carried = 0, own = std::abs(m(r, 3));
    for (int c = 0; c < 3; ++c) carried += std::abs(m(r, c)) * o.error[c], own += std::abs(m(r, c) * o.p[c]);
    s.error[r] = (1 + rounding_gamma(3)) * carried + rounding_gamma(3) * own;
  }
  s.p = m.point(o.p);
  // Embree's intersection and its rtcGetGeometryTransform still differ by ~3e-7 of the distance from the
  // object's origin (tests/geometry/moving_geometry_test.cpp finds repeated hits below that): ten times
  // as much joins the bound.
  s.error += Vec3f(length(m.vector(o.p)) * kInstanceMismatch);
  // A ray leaving p reaches Embree in object space: its origin rounded once more through the inverse.
  // That rounding, carried back through |M|, joins the bound, or the offset origin could land on the
  // object-space surface it leaves and meet it again at t = 0.
  Vec3f origin_error;
  for (int c = 0; c < 3; ++c) {
    float own = std::abs(inv(c, 3));
    for (int k = 0; k < 3; ++k) own += std::abs(inv(c, k) * s.p[k]);
    origin_error[c] = rounding_gamma(3) * own;
  }
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) s.error[r] += std::abs(m(r, c)) * origin_error[c];
  s.ng = normalize(m.normal(o.ng)), s.ns = normalize(m.normal(o.ns));
  s.dpdu = m.vector(o.dpdu), s.dpdv = m.vector(o.dpdv);
  return s;
}

// The record of surface `s` of shape `sh` hit by a ray along world_dir. Every field is written, and the
// record has no padding: no zero-fill first.
[[gnu::always_inline]] inline void write_record(const Surface &s, const ShapeRecord &sh,
                                                const Vec3f &world_dir, nimbus_interaction_t &out) {
  static_assert(sizeof(nimbus_interaction_t) == 22 * sizeof(float));
  s.p.store(out.p);
  out.eps = offset_distance(s.ng, s.error);
  s.ng.store(out.ng);
  s.ns.store(out.ns);
  s.dpdu.store(out.dpdu);
  s.dpdv.store(out.dpdv);
  out.uv[0] = s.uv.x, out.uv[1] = s.uv.y;
  out.material = sh.material;
  out.light_id = sh.light_id;
  out.flags = (dot(world_dir, s.ng) < 0 ? NIMBUS_IX_FRONT_FACE : 0u) |
              (sh.light_id != NIMBUS_NONE ? NIMBUS_IX_EMISSIVE : 0u) |
              (sh.two_sided ? NIMBUS_IX_TWO_SIDED : 0u);
}

}  // namespace

void GeometryScene::interaction(const nimbus_ray_t &ray, const nimbus_hit_t &hit, nimbus_interaction_t &out,
                                float time) const {
  const ShapeRecord &sh = shapes_[hit.geom_id];
  const Vec3f world_dir = Vec3f::load(ray.dir);
  const bool triangle = sh.type != ShapeType::Sphere && sh.type != ShapeType::Disk;
  if (triangle && !sh.motion && !sh.mesh->deforms()) {
    const MeshData &m = *sh.mesh;
    const Corners c(m, hit.prim_id);
    write_record(triangle_surface(m, c, hit.u, hit.v), sh, world_dir, out);
    return;
  }
  // Analytic shapes are computed where they are defined: a moving one in object space at the ray's time
  // (Embree's instance hit distance t holds there too), carried back to world space below.
  Vec3f org = Vec3f::load(ray.org), dir = world_dir;
  std::optional<Transform> to_world, to_object;  // evaluated once per hit, and only for a moving shape
  if (sh.motion) to_world = instance_transform(sh, time), to_object = to_world->inverse();
  if (sh.motion && !triangle) org = to_object->point(org), dir = to_object->vector(dir);
  Surface s;
  if (sh.type == ShapeType::Sphere) {
    s = sphere_surface(sh, org, dir, hit.t);
  } else if (sh.type == ShapeType::Disk) {
    s = disk_surface(sh, org, dir, hit.t);
  } else {
    // The triangle at the ray's time: a deforming mesh's vertices (and normals) between two time steps,
    // interpolated linearly as Embree does.
    const MeshData &m = *sh.mesh;
    Corners c(m, hit.prim_id);
    if (m.deforms()) {
      const GridPosition g = grid_position(embree_time(time), m.position_steps.size());
      const auto lerp = [&](const std::vector<std::vector<Vec3f>> &steps, uint32_t i) {
        return steps[g.step][i] * (1 - g.between) + steps[g.step + 1][i] * g.between;
      };
      for (int k = 0; k < 3; ++k) c.v[k] = lerp(m.position_steps, c.i[k]);
      if (!m.normal_steps.empty())
        for (int k = 0; k < 3; ++k) c.n[k] = lerp(m.normal_steps, c.i[k]);
    }
    s = triangle_surface(m, c, hit.u, hit.v);
  }
  if (sh.motion) s = moved(s, *to_world, *to_object);
  write_record(s, sh, world_dir, out);
}

}  // namespace nimbus
