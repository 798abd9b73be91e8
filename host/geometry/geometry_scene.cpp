#include "geometry/geometry_scene.hpp"

#include <algorithm>
#include <cstring>
#include <optional>
#include <string>

#include "geometry/analytic_shapes.hpp"

namespace nimbus {
namespace {

float triangle_area(const Vec3f &a, const Vec3f &b, const Vec3f &c) {
  return 0.5f * length(cross(b - a, c - a));
}

// A deforming mesh has one vertex buffer per time step, which Embree interpolates at each ray's time.
RTCGeometry make_triangle_geometry(RTCDevice device, const MeshData &mesh) {
  RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  const bool deforms = mesh.deforms();
  if (deforms) rtcSetGeometryTimeStepCount(g, unsigned(mesh.position_steps.size()));
  const size_t steps = deforms ? mesh.position_steps.size() : 1;
  for (size_t s = 0; s < steps; ++s) {
    const std::vector<Vec3f> &positions = deforms ? mesh.position_steps[s] : mesh.positions;
    // Embree reads 16 bytes per vertex (SSE loads): allocate through Embree so the padding is handled.
    auto *v = static_cast<float *>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_VERTEX, unsigned(s), RTC_FORMAT_FLOAT3, 3 * sizeof(float), positions.size()));
    for (size_t i = 0; i < positions.size(); ++i) positions[i].store(v + 3 * i);
  }
  auto *idx = static_cast<uint32_t *>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                              3 * sizeof(uint32_t), mesh.indices.size() / 3));
  std::memcpy(idx, mesh.indices.data(), mesh.indices.size() * sizeof(uint32_t));
  rtcCommitGeometry(g);
  return g;
}

void set_vec(float out[3], const Vec3f &v) { v.store(out); }

// Embree's robust mode (watertight triangle tests) where the scene needs it. Its cost is 20 % of a path
// tracer's time (docs/performance.md §1), and its gain is confined to objects far from the origin for
// their size: there the fast test's cracks at shared edges grow with the coordinates' ulp relative to the
// object, and a sealed box of size 2 leaks light from 2000 units out (580 times its diagonal;
// tests/extremes/leak_test.cpp), while near the origin no render has shown a crack at any scale. Robust
// mode is chosen when some object lies farther from the origin than kRobustBeyond times its own size:
// nine times below the first leak seen.
constexpr float kRobustBeyond = 64;

bool far_for_its_size(const Vec3f &lo, const Vec3f &hi) {
  const float reach = max_component(max(abs(lo), abs(hi)));
  return reach > kRobustBeyond * length(hi - lo);
}

// A moving shape: its object-space geometry (released here) in a scene of their own, instanced with one
// transform per time step (Embree interpolates them at each ray's time, as MotionTransform::at does).
RTCGeometry make_moving_instance(RTCDevice device, RTCGeometry own, const MotionTransform &motion,
                                 RTCScene &object_scene) {
  object_scene = rtcNewScene(device);
  rtcSetSceneFlags(object_scene, RTC_SCENE_FLAG_ROBUST);  // moving shapes are rare: no fast path needed
  rtcAttachGeometryByID(object_scene, own, 0);
  rtcReleaseGeometry(own);
  rtcCommitScene(object_scene);
  RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_INSTANCE);
  rtcSetGeometryInstancedScene(g, object_scene);
  const std::vector<Decomposed> &steps = motion.steps();
  rtcSetGeometryTimeStepCount(g, unsigned(steps.size()));
  for (size_t s = 0; s < steps.size(); ++s) {
    const Decomposed &d = steps[s];
    RTCQuaternionDecomposition q;
    rtcInitQuaternionDecomposition(&q);
    rtcQuaternionDecompositionSetScale(&q, d.scale_skew[0], d.scale_skew[1], d.scale_skew[2]);
    rtcQuaternionDecompositionSetSkew(&q, d.scale_skew[3], d.scale_skew[4], d.scale_skew[5]);
    rtcQuaternionDecompositionSetShift(&q, d.shift[0], d.shift[1], d.shift[2]);
    rtcQuaternionDecompositionSetQuaternion(&q, d.rotation.r, d.rotation.i, d.rotation.j, d.rotation.k);
    rtcQuaternionDecompositionSetTranslation(&q, d.translation[0], d.translation[1], d.translation[2]);
    rtcSetGeometryTransformQuaternion(g, unsigned(s), &q);
  }
  rtcCommitGeometry(g);
  return g;
}

}  // namespace

Expected<std::unique_ptr<GeometryScene>> GeometryScene::build(const SceneDesc &desc) {
  std::unique_ptr<GeometryScene> gs(new GeometryScene());
  gs->device_ = rtcNewDevice(nullptr);
  if (!gs->device_)
    return Error{"cannot create the Embree device (error " + std::to_string(rtcGetDeviceError(nullptr)) +
                 ")"};
  gs->scene_ = rtcNewScene(gs->device_);
  rtcSetSceneBuildQuality(gs->scene_, RTC_BUILD_QUALITY_HIGH);

  gs->shapes_.reserve(desc.shapes.size());  // records are Embree user pointers: no reallocation after this
  for (const ShapeDesc &sd : desc.shapes) {
    ShapeRecord rec;
    rec.type = sd.type;
    rec.material = sd.material;
    rec.two_sided = sd.two_sided;
    rec.center = sd.center;
    rec.normal = sd.normal;
    rec.radius = sd.radius;
    // The shape's own geometry and bounds: world space, or object space when it moves (its area then too).
    const bool analytic = sd.type == ShapeType::Sphere || sd.type == ShapeType::Disk;
    Vec3f lo(kInfinity), hi(-kInfinity);
    if (analytic) {
      rec.area = sd.type == ShapeType::Sphere ? 4 * kPi * sqr(sd.radius) : kPi * sqr(sd.radius);
      lo = sd.center - Vec3f(sd.radius), hi = sd.center + Vec3f(sd.radius);
    } else {
      rec.mesh = &sd.mesh;
      const auto &p = sd.mesh.positions;
      for (size_t t = 0; t + 2 < sd.mesh.indices.size(); t += 3)
        rec.area +=
            triangle_area(p[sd.mesh.indices[t]], p[sd.mesh.indices[t + 1]], p[sd.mesh.indices[t + 2]]);
      for (const Vec3f &q : p) lo = min(lo, q), hi = max(hi, q);
      for (const std::vector<Vec3f> &step : sd.mesh.position_steps)
        for (const Vec3f &q : step) lo = min(lo, q), hi = max(hi, q);
      if (sd.mesh.deforms() && sd.mesh.steps_close > sd.mesh.steps_open) {  // else every ray sees step 0
        gs->moves_ = true;
        gs->shutter_open_ = sd.mesh.steps_open, gs->shutter_close_ = sd.mesh.steps_close;
      }
    }
    rec.motion = sd.motion.get();
    gs->shapes_.push_back(rec);
    RTCGeometry g = analytic ? make_analytic_geometry(gs->device_, gs->shapes_.back())
                             : make_triangle_geometry(gs->device_, sd.mesh);
    if (sd.motion) {
      // The object's box at every time step (its sweep between steps stays near them).
      for (const Decomposed &d : sd.motion->steps())
        for (int c = 0; c < 8; ++c) {
          const Vec3f w = d.matrix().point({c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z});
          gs->bounds_min_ = min(gs->bounds_min_, w), gs->bounds_max_ = max(gs->bounds_max_, w);
        }
      if (sd.motion->moves()) {
        gs->moves_ = true;
        gs->shutter_open_ = sd.motion->open(), gs->shutter_close_ = sd.motion->close();
      }
      RTCScene object_scene = nullptr;
      g = make_moving_instance(gs->device_, g, *sd.motion, object_scene);
      gs->shapes_.back().instance = g;
      gs->object_scenes_.push_back(object_scene);
    } else {
      gs->bounds_min_ = min(gs->bounds_min_, lo), gs->bounds_max_ = max(gs->bounds_max_, hi);
      gs->robust_ = gs->robust_ || far_for_its_size(lo, hi);
    }
    rtcAttachGeometryByID(gs->scene_, g, uint32_t(gs->shapes_.size() - 1));
    rtcReleaseGeometry(g);
  }
  if (gs->shapes_.empty()) gs->bounds_min_ = gs->bounds_max_ = Vec3f(0);
  rtcSetSceneFlags(gs->scene_, gs->robust_ ? RTC_SCENE_FLAG_ROBUST : RTC_SCENE_FLAG_NONE);
  rtcCommitScene(gs->scene_);
  if (const RTCError err = rtcGetDeviceError(gs->device_); err != RTC_ERROR_NONE)
    return Error{"Embree failed to build the scene (error " + std::to_string(int(err)) + ")"};
  return gs;
}

// Relative difference between the surface Embree intersects in a moving instance and the one its
// interpolated transform gives, allowed for in the offset distance (interaction).
constexpr float kInstanceMismatch = 0x1p-18f;

// Embree's own interpolation, not MotionTransform::at: Embree's slerp uses approximate trigonometry, and
// a surface point carried by an exact slerp lies off the surface Embree hit by more than the offset
// distance, so rays leaving it would meet the same surface again at t ~ 0 (energy gained at moving glass).
Transform GeometryScene::instance_transform(const ShapeRecord &s, float time) const {
  float m[12];
  rtcGetGeometryTransform(s.instance, embree_time(time), RTC_FORMAT_FLOAT3X4_ROW_MAJOR, m);
  return Transform({m[0], m[1], m[2], m[3], m[4], m[5], m[6], m[7], m[8], m[9], m[10], m[11], 0, 0, 0, 1});
}

GeometryScene::~GeometryScene() {
  if (scene_) rtcReleaseScene(scene_);
  for (RTCScene s : object_scenes_) rtcReleaseScene(s);
  if (device_) rtcReleaseDevice(device_);
}

void GeometryScene::interaction(const nimbus_ray_t &ray, const nimbus_hit_t &hit, nimbus_interaction_t &out,
                                float time) const {
  // Every field of `out` is written below, and the record has no padding: no zero-fill first.
  static_assert(sizeof(nimbus_interaction_t) == 22 * sizeof(float));
  const ShapeRecord &s = shapes_[hit.geom_id];
  // Analytic shapes are computed where they are defined: a moving one in object space at the ray's time
  // (Embree's instance hit distance t holds there too), carried back to world space below.
  const Vec3f world_dir = Vec3f::load(ray.dir);
  Vec3f org = Vec3f::load(ray.org), dir = world_dir;
  // Evaluated once per hit, and only for a moving shape.
  std::optional<Transform> to_world, to_object;
  if (s.motion) to_world = instance_transform(s, time), to_object = to_world->inverse();
  if (s.motion && (s.type == ShapeType::Sphere || s.type == ShapeType::Disk))
    org = to_object->point(org), dir = to_object->vector(dir);
  Vec3f p, ng, ns, dpdu, dpdv;
  Vec2f uv;
  Vec3f error;  // bound on each coordinate's rounding error in p
  switch (s.type) {
    case ShapeType::Sphere: {
      // Re-project the hit onto the sphere: removes the error of o + t d along the ray.
      const Vec3f d = org + dir * hit.t - s.center;
      ng = normalize(d);
      p = s.center + ng * s.radius;
      ns = ng;
      error = sphere_point_error(s.center, ng, s.radius);
      const float phi = std::atan2(ng.y, ng.x), theta = std::acos(clamp(ng.z, -1, 1));
      uv = {(phi < 0 ? phi + 2 * kPi : phi) / (2 * kPi), theta / kPi};
      dpdu = Vec3f{-ng.y, ng.x, 0} * (2 * kPi * s.radius);
      if (length_squared(dpdu) == 0) dpdu = Frame::from_normal(ng).s;
      dpdv = cross(ng, dpdu);
      break;
    }
    case ShapeType::Disk: {
      p = org + dir * hit.t;
      p -= s.normal * dot(p - s.center, s.normal);  // onto the plane
      ng = ns = s.normal;
      const Frame f = Frame::from_normal(s.normal);
      const Vec3f l = f.to_local(p - s.center);
      uv = {0.5f + 0.5f * l.x / s.radius, 0.5f + 0.5f * l.y / s.radius};
      dpdu = f.s, dpdv = f.t;
      error = disk_point_error(p, s.center);
      break;
    }
    default: {
      const MeshData &m = *s.mesh;
      const uint32_t i0 = m.indices[3 * hit.prim_id], i1 = m.indices[3 * hit.prim_id + 1],
                     i2 = m.indices[3 * hit.prim_id + 2];
      // The triangle at the ray's time: a deforming mesh's vertices (and normals) between two time steps,
      // interpolated linearly as Embree does.
      Vec3f p0 = m.positions[i0], p1 = m.positions[i1], p2 = m.positions[i2], n[3];
      if (!m.normals.empty()) n[0] = m.normals[i0], n[1] = m.normals[i1], n[2] = m.normals[i2];
      if (m.deforms()) {
        const GridPosition g = grid_position(embree_time(time), m.position_steps.size());
        const auto lerp = [&](const std::vector<std::vector<Vec3f>> &steps, uint32_t i) {
          return steps[g.step][i] * (1 - g.between) + steps[g.step + 1][i] * g.between;
        };
        p0 = lerp(m.position_steps, i0), p1 = lerp(m.position_steps, i1), p2 = lerp(m.position_steps, i2);
        if (!m.normal_steps.empty())
          n[0] = lerp(m.normal_steps, i0), n[1] = lerp(m.normal_steps, i1), n[2] = lerp(m.normal_steps, i2);
      }
      const float b1 = hit.u, b2 = hit.v, b0 = 1 - b1 - b2;
      // Barycentric interpolation is far more accurate than o + t d (pbrt-v4 section 6.8).
      p = p0 * b0 + p1 * b1 + p2 * b2;
      error = triangle_point_error(p0, p1, p2, b0, b1, b2);
      // Far from the origin a point within an ulp of an edge can round onto the plane of the neighbouring
      // face, where a new ray would meet that face at t = 0 from its far side (a leak at box corners).
      // Nudging the point a few ulps towards the triangle's centroid, within its plane, keeps it strictly
      // inside its own triangle and off every neighbour's plane.
      const Vec3f to_centroid = (p0 + p1 + p2) * (1.0f / 3) - p;
      if (const float dist = length(to_centroid); dist > 0) {
        const float nudge = std::min(max_component(abs(p)) * 0x1p-21f, 0.5f * dist);
        p += to_centroid * (nudge / dist);
        error += abs(p) * rounding_gamma(3);
      }
      const Vec3f e1 = p1 - p0, e2 = p2 - p0;
      ng = oriented_triangle_normal(p0, p1, p2, m.normals.empty() ? nullptr : n, b1, b2);
      Vec2f uv0{0, 0}, uv1{1, 0}, uv2{1, 1};
      if (!m.uvs.empty()) uv0 = m.uvs[i0], uv1 = m.uvs[i1], uv2 = m.uvs[i2];
      uv = {uv0.x * b0 + uv1.x * b1 + uv2.x * b2, uv0.y * b0 + uv1.y * b1 + uv2.y * b2};
      if (m.uvs.empty()) {
        // The general solve below with these default uvs (det = 1), without its division.
        dpdu = e1, dpdv = e2 - e1;
      } else {
        const float du1 = uv1.x - uv0.x, du2 = uv2.x - uv0.x, dv1 = uv1.y - uv0.y, dv2 = uv2.y - uv0.y;
        const float det = du1 * dv2 - dv1 * du2;
        if (std::abs(det) > 1e-12f) {
          dpdu = (e1 * dv2 - e2 * dv1) / det;
          dpdv = (e2 * du1 - e1 * du2) / det;
        } else {
          const Frame f = Frame::from_normal(ng);
          dpdu = f.s, dpdv = f.t;
        }
      }
      ns = ng;
      if (!m.normals.empty()) {
        const Vec3f shading = n[0] * b0 + n[1] * b1 + n[2] * b2;
        if (length_squared(shading) > 0) ns = normalize(shading);
      }
      break;
    }
  }
  if (s.motion) {
    // The object-space surface at the ray's time; the transform's own rounding joins the error bound.
    const Transform &m = *to_world;
    Vec3f moved_error;
    for (int r = 0; r < 3; ++r) {  // pbrt-v4 6.8.6: the carried error through |M|, plus the product's own
      float carried = 0, own = std::abs(m(r, 3));
      for (int c = 0; c < 3; ++c) carried += std::abs(m(r, c)) * error[c], own += std::abs(m(r, c) * p[c]);
      moved_error[r] = (1 + rounding_gamma(3)) * carried + rounding_gamma(3) * own;
    }
    const Vec3f p_object = p;
    p = m.point(p), error = moved_error;
    // Embree's intersection and its rtcGetGeometryTransform still differ by ~3e-7 of the distance from
    // the object's origin (tests/geometry/moving_geometry_test.cpp finds repeated hits below that): ten
    // times as much joins the bound.
    error += Vec3f(length(m.vector(p_object)) * kInstanceMismatch);
    // A ray leaving p reaches Embree in object space: its origin rounded once more through the inverse.
    // That rounding, carried back through |M|, joins the bound, or the offset origin could land on the
    // object-space surface it leaves and meet it again at t = 0.
    const Transform &inv = *to_object;
    Vec3f origin_error;
    for (int c = 0; c < 3; ++c) {
      float own = std::abs(inv(c, 3));
      for (int k = 0; k < 3; ++k) own += std::abs(inv(c, k) * p[k]);
      origin_error[c] = rounding_gamma(3) * own;
    }
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) error[r] += std::abs(m(r, c)) * origin_error[c];
    ng = normalize(m.normal(ng)), ns = normalize(m.normal(ns));
    dpdu = m.vector(dpdu), dpdv = m.vector(dpdv);
  }
  set_vec(out.p, p);
  out.eps = offset_distance(ng, error);
  set_vec(out.ng, ng);
  set_vec(out.ns, ns);
  set_vec(out.dpdu, dpdu);
  set_vec(out.dpdv, dpdv);
  out.uv[0] = uv.x, out.uv[1] = uv.y;
  out.material = s.material;
  out.light_id = s.light_id;
  out.flags = (dot(world_dir, ng) < 0 ? NIMBUS_IX_FRONT_FACE : 0u) |
              (s.light_id != NIMBUS_NONE ? NIMBUS_IX_EMISSIVE : 0u) |
              (s.two_sided ? NIMBUS_IX_TWO_SIDED : 0u);
}

}  // namespace nimbus
