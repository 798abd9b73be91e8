// The scene's geometry in Embree 3: one Embree geometry per scene shape (geom_id = shape index),
// closest-hit and occlusion queries, and the surface details (interaction) of a hit. Shapes that move
// over the shutter are Embree instances with time steps (rigid motion) or meshes with one vertex buffer
// per time step (deformation); queries then take the scene time of the ray.
#pragma once

#include <embree3/rtcore.h>
#if defined(__SSE2__)
#include <xmmintrin.h>
#endif
#include <nimbus/scene.h>

#include <algorithm>
#include <cstddef>
#include <memory>
#include <vector>

#include <nimbus/cpp/math.hpp>
#include "core/expected.hpp"
#include "scene/scene_desc.hpp"

namespace nimbus {

// What the host knows about a shape beyond its triangles: material, emitter, analytic parameters.
struct ShapeRecord {
  ShapeType type = ShapeType::Mesh;
  uint32_t material = 0;
  uint32_t light_id = NIMBUS_NONE;  // set by the light set when the shape emits
  bool two_sided = false;
  Vec3f center, normal;  // sphere, disk
  float radius = 0;
  const MeshData *mesh = nullptr;  // triangle shapes: points into the SceneDesc (kept alive by the owner)
  float area = 0;
  // A moving shape (its geometry in object space, an Embree instance with time steps); null when static.
  const MotionTransform *motion = nullptr;
  RTCGeometry instance = nullptr;  // that instance (the scene holds it)
};

class GeometryScene {
 public:
  // Builds the BVH. `desc` must outlive the GeometryScene (meshes are referenced, not copied).
  static Expected<std::unique_ptr<GeometryScene>> build(const SceneDesc &desc);
  ~GeometryScene();
  // Whether Embree runs its watertight (robust) triangle test: some object is far from the origin for its
  // size.
  bool watertight() const { return robust_; }
  GeometryScene(const GeometryScene &) = delete;
  GeometryScene &operator=(const GeometryScene &) = delete;

  // Queries at scene time `time` (within the shutter; static scenes ignore it).
  // Closest hit and any hit; inline, at the end of this file.
  void intersect(const nimbus_ray_t &ray, nimbus_hit_t &hit, float time = 0) const;
  bool occluded(const nimbus_ray_t &ray, float time = 0) const;
  void interaction(const nimbus_ray_t &ray, const nimbus_hit_t &hit, nimbus_interaction_t &out,
                   float time = 0) const;
  // Whether some shape moves over the shutter (rays then need their time).
  bool moves() const { return moves_; }

  RTCScene rtc_scene() const { return scene_; }  // for benchmarks against Embree itself
  std::vector<ShapeRecord> &shapes() { return shapes_; }
  const std::vector<ShapeRecord> &shapes() const { return shapes_; }
  Vec3f bounds_min() const { return bounds_min_; }
  Vec3f bounds_max() const { return bounds_max_; }
  // Bounding sphere of everything (centre, radius).
  Vec3f sphere_center() const { return (bounds_min_ + bounds_max_) * 0.5f; }
  float sphere_radius() const { return 0.5f * length(bounds_max_ - bounds_min_); }

 private:
  GeometryScene() = default;
  // Scene time to Embree's [0, 1] over the shutter (inline: every ray asks).
  float embree_time(float time) const {
    return moves_ ? std::clamp((time - shutter_open_) / (shutter_close_ - shutter_open_), 0.0f, 1.0f) : 0.0f;
  }
  // interaction() for shapes that move or are not triangles (hit_interaction.cpp).
  void moving_or_analytic_interaction(const nimbus_ray_t &ray, const nimbus_hit_t &hit,
                                      nimbus_interaction_t &out, float time) const;
  // A moving shape's object-to-world transform at scene time `time`, as Embree's intersection used it.
  Transform instance_transform(const ShapeRecord &s, float time) const;
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  std::vector<ShapeRecord> shapes_;
  Vec3f bounds_min_{kInfinity}, bounds_max_{-kInfinity};
  std::vector<RTCScene> object_scenes_;  // the moving meshes' own scenes (instanced)
  bool moves_ = false;
  bool robust_ =
      false;  // Embree's watertight triangle test (some object is far from the origin for its size)
  float shutter_open_ = 0, shutter_close_ = 0;  // Embree's ray time [0, 1] spans it
};

// A triangle's unit geometric normal by its winding (right-handed). V: Vec3f, or Lanes3 (core/lanes3.hpp),
// which gives the same bits.
template <class V>
V triangle_normal(const V &p0, const V &p1, const V &p2) {
  return normalize(cross(p1 - p0, p2 - p0));
}
// A triangle's geometric normal ng turned, if need be, towards its interpolated vertex normal `shading`.
template <class V>
V towards_shading(const V &ng, const V &shading) {
  return dot(shading, ng) < 0 ? -ng : ng;
}
// Geometric normal of a triangle, oriented like the interaction's ng: towards the interpolated shading
// normal when there are vertex normals (n, three of them, or null), else by the winding.
inline Vec3f oriented_triangle_normal(const Vec3f &p0, const Vec3f &p1, const Vec3f &p2, const Vec3f *n,
                                      float b1, float b2) {
  const Vec3f ng = triangle_normal(p0, p1, p2);
  return n ? towards_shading(ng, n[0] * (1 - b1 - b2) + n[1] * b1 + n[2] * b2) : ng;
}
// The same for triangle `prim` of a mesh (its rest positions).
inline Vec3f oriented_triangle_normal(const MeshData &m, uint32_t prim, float b1, float b2) {
  const uint32_t i0 = m.indices[3 * prim], i1 = m.indices[3 * prim + 1], i2 = m.indices[3 * prim + 2];
  const Vec3f n[3] = {m.normals.empty() ? Vec3f() : m.normals[i0],
                      m.normals.empty() ? Vec3f() : m.normals[i1],
                      m.normals.empty() ? Vec3f() : m.normals[i2]};
  return oriented_triangle_normal(m.positions[i0], m.positions[i1], m.positions[i2],
                                  m.normals.empty() ? nullptr : n, b1, b2);
}

// pbrt-v4's gamma(n): the relative error bound of n chained float operations (u = 2^-24).
constexpr float rounding_gamma(int n) { return float(n) * 0x1p-24f / (1 - float(n) * 0x1p-24f); }

// Bounds on each coordinate's rounding error of points computed on a shape (pbrt-v4 section 6.8): shared by
// ray hits (GeometryScene::interaction) and light samples (area_light.cpp), which compute them alike.
// A point re-projected onto a sphere: center + n * radius.
inline Vec3f sphere_point_error(const Vec3f &center, const Vec3f &n, float radius) {
  return (abs(center) + abs(n) * radius) * rounding_gamma(5);
}
// A point projected into a disk's plane or placed in it from its centre.
inline Vec3f disk_point_error(const Vec3f &p, const Vec3f &center) {
  return (abs(p) + abs(center)) * rounding_gamma(6);
}
// A point interpolated on a triangle with barycentrics b0, b1, b2 (V: Vec3f or Lanes3).
template <class V>
V triangle_point_error(const V &p0, const V &p1, const V &p2, float b0, float b1, float b2) {
  return (abs(p0 * b0) + abs(p1 * b1) + abs(p2 * b2)) * rounding_gamma(7);
}

// The distance along ng that takes a point off its surface when each coordinate of the point is off by at
// most the matching component of `error` (pbrt-v4 section 6.8.6): error is per axis, so a floor at z = 0
// far out along x gets an offset of a few ulps of z, not of x. V: Vec3f or Lanes3.
template <class V>
float offset_distance(const V &ng, const V &error) {
  return std::max(dot(abs(ng), error), 0x1p-126f);
}

// A ray leaving p along dir: the origin pushed by eps along the side of ng that dir points to, then each
// moved coordinate rounded one more ulp away from the surface, so that rounding of the sum can never
// leave the origin on the surface it leaves.
inline Vec3f offset_origin(const Vec3f &p, const Vec3f &ng, float eps, const Vec3f &dir) {
  const Vec3f offset = ng * (dot(ng, dir) >= 0 ? eps : -eps);
  Vec3f o = p + offset;
  const auto away = [](float v, float d) {
    return d > 0 ? next_float(v, true) : d < 0 ? next_float(v, false) : v;
  };
  return {away(o.x, offset.x), away(o.y, offset.y), away(o.z, offset.z)};
}

// Embree's ray as it reads it: (org, tnear) and (dir, time) each with one 16-byte load. Written with one
// 16-byte store each, the load takes the stored value straight from the store buffer; written as separate
// floats, the wider load must wait until they have reached the cache (a store-forwarding stall per ray).
inline void store_embree_ray(const nimbus_ray_t &ray, float time, RTCRay &out) {
#if defined(__SSE2__)
  static_assert(offsetof(RTCRay, tnear) == 12 && offsetof(RTCRay, time) == 28 && alignof(RTCRay) >= 16);
  _mm_store_ps(&out.org_x, _mm_setr_ps(ray.org[0], ray.org[1], ray.org[2], ray.tnear));
  _mm_store_ps(&out.dir_x, _mm_setr_ps(ray.dir[0], ray.dir[1], ray.dir[2], time));
#else
  out.org_x = ray.org[0], out.org_y = ray.org[1], out.org_z = ray.org[2], out.tnear = ray.tnear;
  out.dir_x = ray.dir[0], out.dir_y = ray.dir[1], out.dir_z = ray.dir[2], out.time = time;
#endif
  out.tfar = ray.tfar, out.mask = 0xFFFFFFFFu, out.id = 0, out.flags = 0;
}

// The ray queries, defined here so that the scene services (abi/scene_service.cpp), which call them for
// every ray, inline them.
inline void GeometryScene::intersect(const nimbus_ray_t &ray, nimbus_hit_t &hit, float time) const {
  if (!(ray.tnear <= ray.tfar)) {  // inactive ray
    hit.geom_id = NIMBUS_NONE;
    return;
  }
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRayHit rh;
  store_embree_ray(ray, embree_time(time), rh.ray);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_, &ctx, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
    hit = {kInfinity, 0, 0, NIMBUS_NONE, NIMBUS_NONE, NIMBUS_NONE};
    return;
  }
  // A moving mesh is hit inside its instance: the shape is the instance's id.
  const bool instanced = rh.hit.instID[0] != RTC_INVALID_GEOMETRY_ID;
  hit = {rh.ray.tfar,   rh.hit.u,   rh.hit.v, instanced ? rh.hit.instID[0] : rh.hit.geomID,
         rh.hit.primID, NIMBUS_NONE};
}

inline bool GeometryScene::occluded(const nimbus_ray_t &ray, float time) const {
  if (!(ray.tnear <= ray.tfar)) return false;
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRay r;
  store_embree_ray(ray, embree_time(time), r);
  rtcOccluded1(scene_, &ctx, &r);
  return r.tfar < 0;
}

}  // namespace nimbus
