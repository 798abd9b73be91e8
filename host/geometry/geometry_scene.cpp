#include "geometry/geometry_scene.hpp"

#include <algorithm>
#include <cstring>
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
// Embree tests rays against it in object space, so the robust test follows the object-space bounds, by
// the same rule as the world's scene (robust).
RTCGeometry make_moving_instance(RTCDevice device, RTCGeometry own, const MotionTransform &motion,
                                 bool robust, RTCScene &object_scene) {
  object_scene = rtcNewScene(device);
  rtcSetSceneFlags(object_scene, robust ? RTC_SCENE_FLAG_ROBUST : RTC_SCENE_FLAG_NONE);
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
      g = make_moving_instance(gs->device_, g, *sd.motion, far_for_its_size(lo, hi), object_scene);
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

}  // namespace nimbus
