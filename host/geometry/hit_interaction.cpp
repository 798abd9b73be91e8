// GeometryScene::interaction: the surface record of a ray hit. Each shape computes its surface where it is
// defined (a moving one in object space at the ray's time), a moving shape's is carried to world space,
// and one function writes the record. A static triangle, nearly every hit of a production scene, takes a
// path of its own without the motion and analytic-shape branches, in four-wide arithmetic (Lanes3) that
// rounds exactly as Vec3f's.
#include <cmath>
#include <cstddef>
#include <optional>

#include "core/lanes3.hpp"
#include "geometry/geometry_scene.hpp"

namespace nimbus {
namespace {

// A hit's surface before the record is written; error bounds each coordinate's rounding error in p. The
// functions that fill and write it are forced inline: called, they pass it through memory, which costs
// more than the split saves. Its vectors are four-wide (Lanes3), for the triangle's sake: the analytic
// shapes and motion compute in Vec3f and convert.
struct Surface {
  Lanes3 p, error, ng, ns, dpdu, dpdv;
  Vec2f uv;
};

// Triangle prim's corner indices and rest positions (and vertex normals, when the mesh has them).
struct Corners {
  uint32_t i[3];
  Lanes3 v[3], n[3];
  Corners(const MeshData &m, uint32_t prim)
      : i{m.indices[3 * prim], m.indices[3 * prim + 1], m.indices[3 * prim + 2]},
        v{Lanes3::load_settled(&m.positions[i[0]].x), Lanes3::load_settled(&m.positions[i[1]].x),
          Lanes3::load_settled(&m.positions[i[2]].x)} {
    if (!m.normals.empty())
      for (int k = 0; k < 3; ++k) n[k] = Lanes3::load_settled(&m.normals[i[k]].x);
  }
};

// The hit at barycentrics (b1, b2) of the triangle with corners c of mesh m: its rest positions, or a
// deforming mesh's at the ray's time, four-wide.
[[gnu::always_inline]] inline Surface triangle_surface(const MeshData &m, const Corners &c, float b1,
                                                       float b2) {
  const Lanes3 &v0 = c.v[0], &v1 = c.v[1], &v2 = c.v[2];
  const bool has_normals = !m.normals.empty();
  const uint32_t i0 = c.i[0], i1 = c.i[1], i2 = c.i[2];
  Surface s;
  const float b0 = 1 - b1 - b2;
  // Barycentric interpolation is far more accurate than o + t d (pbrt-v4 section 6.8).
  s.p = v0 * b0 + v1 * b1 + v2 * b2;
  s.error = triangle_point_error(v0, v1, v2, b0, b1, b2);
  // Far from the origin a point within an ulp of an edge can round onto the plane of the neighbouring
  // face, where a new ray would meet that face at t = 0 from its far side (a leak at box corners).
  // Nudging the point a few ulps towards the triangle's centroid, within its plane, keeps it strictly
  // inside its own triangle and off every neighbour's plane.
  const Lanes3 to_centroid = (v0 + v1 + v2) * (1.0f / 3) - s.p;
  if (const float dist = length(to_centroid); dist > 0) {
    const float nudge = std::min(max_component(abs(s.p)) * 0x1p-21f, 0.5f * dist);
    s.p = s.p + to_centroid * (nudge / dist);
    s.error = s.error + abs(s.p) * rounding_gamma(3);
  }
  const Lanes3 e1 = v1 - v0, e2 = v2 - v0;
  s.ng = triangle_normal(v0, v1, v2);
  if (has_normals) {
    const Lanes3 shading = c.n[0] * b0 + c.n[1] * b1 + c.n[2] * b2;
    s.ng = towards_shading(s.ng, shading);  // as oriented_triangle_normal
    s.ns = dot(shading, shading) > 0 ? normalize(shading) : s.ng;
  } else {
    s.ns = s.ng;
  }
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
      const float inv = 1.0f / det;  // Vec3f's division: a multiply by the reciprocal
      s.dpdu = (e1 * dv2 - e2 * dv1) * inv;
      s.dpdv = (e2 * du1 - e1 * du2) * inv;
    } else {
      const Frame f = Frame::from_normal(s.ng.vec3());
      s.dpdu = Lanes3::of(f.s), s.dpdv = Lanes3::of(f.t);
    }
  }
  return s;
}

// A surface computed in Vec3f.
Surface surface_of(const Vec3f &p, const Vec3f &error, const Vec3f &ng, const Vec3f &ns, const Vec3f &dpdu,
                   const Vec3f &dpdv, const Vec2f &uv) {
  return {Lanes3::of(p),
          Lanes3::of(error),
          Lanes3::of(ng),
          Lanes3::of(ns),
          Lanes3::of(dpdu),
          Lanes3::of(dpdv),
          uv};
}

// The hit on a sphere, re-projected onto it: removes the error of o + t d along the ray.
Surface sphere_surface(const ShapeRecord &sh, const Vec3f &org, const Vec3f &dir, float t) {
  const Vec3f ng = normalize(org + dir * t - sh.center);
  const float phi = std::atan2(ng.y, ng.x), theta = std::acos(clamp(ng.z, -1, 1));
  Vec3f dpdu = Vec3f{-ng.y, ng.x, 0} * (2 * kPi * sh.radius);
  if (length_squared(dpdu) == 0) dpdu = Frame::from_normal(ng).s;
  return surface_of(sh.center + ng * sh.radius, sphere_point_error(sh.center, ng, sh.radius), ng, ng, dpdu,
                    cross(ng, dpdu), {(phi < 0 ? phi + 2 * kPi : phi) / (2 * kPi), theta / kPi});
}

// The hit on a disk, projected onto its plane.
Surface disk_surface(const ShapeRecord &sh, const Vec3f &org, const Vec3f &dir, float t) {
  Vec3f p = org + dir * t;
  p -= sh.normal * dot(p - sh.center, sh.normal);
  const Frame f = Frame::from_normal(sh.normal);
  const Vec3f l = f.to_local(p - sh.center);
  return surface_of(p, disk_point_error(p, sh.center), sh.normal, sh.normal, f.s, f.t,
                    {0.5f + 0.5f * l.x / sh.radius, 0.5f + 0.5f * l.y / sh.radius});
}

// Relative difference between the surface Embree intersects in a moving instance and the one its
// interpolated transform gives, allowed for in the offset distance.
constexpr float kInstanceMismatch = 0x1p-18f;

// An object-space surface carried to world space by a moving shape's transform at the ray's time
// (to_world, and its inverse to_object); the transform's own rounding joins the error bound.
Surface moved(const Surface &o, const Transform &m, const Transform &inv) {
  const Vec3f op = o.p.vec3(), oerror = o.error.vec3();
  Vec3f p, error;
  for (int r = 0; r < 3; ++r) {  // pbrt-v4 6.8.6: the carried error through |M|, plus the product's own
    float carried = 0, own = std::abs(m(r, 3));
    for (int c = 0; c < 3; ++c) carried += std::abs(m(r, c)) * oerror[c], own += std::abs(m(r, c) * op[c]);
    error[r] = (1 + rounding_gamma(3)) * carried + rounding_gamma(3) * own;
  }
  p = m.point(op);
  // Embree's intersection and its rtcGetGeometryTransform still differ by ~3e-7 of the distance from the
  // object's origin (tests/geometry/moving_geometry_test.cpp finds repeated hits below that): ten times
  // as much joins the bound.
  error += Vec3f(length(m.vector(op)) * kInstanceMismatch);
  // A ray leaving p reaches Embree in object space: its origin rounded once more through the inverse.
  // That rounding, carried back through |M|, joins the bound, or the offset origin could land on the
  // object-space surface it leaves and meet it again at t = 0.
  Vec3f origin_error;
  for (int c = 0; c < 3; ++c) {
    float own = std::abs(inv(c, 3));
    for (int k = 0; k < 3; ++k) own += std::abs(inv(c, k) * p[k]);
    origin_error[c] = rounding_gamma(3) * own;
  }
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) error[r] += std::abs(m(r, c)) * origin_error[c];
  return surface_of(p, error, normalize(m.normal(o.ng.vec3())), normalize(m.normal(o.ns.vec3())),
                    m.vector(o.dpdu.vec3()), m.vector(o.dpdv.vec3()), o.uv);
}

// The record of surface `s` of shape `sh` hit by a ray along world_dir. Every field is written, and the
// record has no padding: no zero-fill first. Its first 64 bytes go out in four 16-byte stores.
[[gnu::always_inline]] inline void write_record(const Surface &s, const ShapeRecord &sh,
                                                const Lanes3 &world_dir, nimbus_interaction_t &out) {
  static_assert(sizeof(nimbus_interaction_t) == 22 * sizeof(float));
  static_assert(offsetof(nimbus_interaction_t, ng) == 16 && offsetof(nimbus_interaction_t, ns) == 28 &&
                offsetof(nimbus_interaction_t, dpdu) == 40 && offsetof(nimbus_interaction_t, dpdv) == 52);
  Lanes3::Floats p_eps = s.p.v;
  p_eps[3] = offset_distance(s.ng, s.error);
  auto *bytes = reinterpret_cast<unsigned char *>(&out);
  store4(bytes, p_eps);
  store4(bytes + 16, __builtin_shufflevector(s.ng.v, s.ns.v, 0, 1, 2, 4));
  store4(bytes + 32, __builtin_shufflevector(s.ns.v, s.dpdu.v, 1, 2, 4, 5));
  store4(bytes + 48, __builtin_shufflevector(s.dpdu.v, s.dpdv.v, 2, 4, 5, 6));
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
  const bool triangle = sh.type != ShapeType::Sphere && sh.type != ShapeType::Disk;
  if (triangle && !sh.motion && !sh.mesh->deforms()) {
    const MeshData &m = *sh.mesh;
    const Corners c(m, hit.prim_id);
    write_record(triangle_surface(m, c, hit.u, hit.v), sh, Lanes3::load(ray.dir), out);
    return;
  }
  moving_or_analytic_interaction(ray, hit, out, time);
}

// Out of line, so that the static triangle's path above saves no registers for it.
[[gnu::noinline]] void GeometryScene::moving_or_analytic_interaction(const nimbus_ray_t &ray,
                                                                     const nimbus_hit_t &hit,
                                                                     nimbus_interaction_t &out,
                                                                     float time) const {
  const ShapeRecord &sh = shapes_[hit.geom_id];
  const Vec3f world_dir = Vec3f::load(ray.dir);
  const bool triangle = sh.type != ShapeType::Sphere && sh.type != ShapeType::Disk;
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
      for (int k = 0; k < 3; ++k) c.v[k] = Lanes3::of(lerp(m.position_steps, c.i[k]));
      if (!m.normal_steps.empty())
        for (int k = 0; k < 3; ++k) c.n[k] = Lanes3::of(lerp(m.normal_steps, c.i[k]));
    }
    s = triangle_surface(m, c, hit.u, hit.v);
  }
  if (sh.motion) s = moved(s, *to_world, *to_object);
  write_record(s, sh, Lanes3::of(world_dir), out);
}

}  // namespace nimbus
