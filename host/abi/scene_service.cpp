// nimbus.host.scene-query@1 and nimbus.host.camera@1.
#include "abi/host_services.hpp"
#include "abi/service_tables.hpp"

namespace nimbus {
namespace {

void count_rays(RunState &run, const nimbus_thread_ctx_t *tc, uint32_t n) {
  if (tc && tc->worker_index < run.ray_counters.size()) run.ray_counters[tc->worker_index].rays += n;
}

void intersect(const nimbus_host_t *host, const nimbus_thread_ctx_t *tc, const nimbus_ray_t *rays,
               nimbus_hit_t *hits, uint32_t n) {
  count_rays(run_of(host), tc, n);
  const GeometryScene &g = *world_of(host).geometry;
  for (uint32_t i = 0; i < n; ++i) g.intersect(rays[i], hits[i]);
}

void occluded(const nimbus_host_t *host, const nimbus_thread_ctx_t *tc, const nimbus_ray_t *rays,
              uint8_t *blocked, uint32_t n) {
  count_rays(run_of(host), tc, n);
  const GeometryScene &g = *world_of(host).geometry;
  for (uint32_t i = 0; i < n; ++i) blocked[i] = g.occluded(rays[i]) ? 1 : 0;
}

void interaction(const nimbus_host_t *host, const nimbus_ray_t *ray, const nimbus_hit_t *hit,
                 nimbus_interaction_t *out) {
  world_of(host).geometry->interaction(*ray, *hit, *out);
}

void intersect_at(const nimbus_host_t *host, const nimbus_thread_ctx_t *tc, const nimbus_ray_t *rays,
                  const float *times, nimbus_hit_t *hits, uint32_t n) {
  count_rays(run_of(host), tc, n);
  const GeometryScene &g = *world_of(host).geometry;
  for (uint32_t i = 0; i < n; ++i) g.intersect(rays[i], hits[i], times[i]);
}

void occluded_at(const nimbus_host_t *host, const nimbus_thread_ctx_t *tc, const nimbus_ray_t *rays,
                 const float *times, uint8_t *blocked, uint32_t n) {
  count_rays(run_of(host), tc, n);
  const GeometryScene &g = *world_of(host).geometry;
  for (uint32_t i = 0; i < n; ++i) blocked[i] = g.occluded(rays[i], times[i]) ? 1 : 0;
}

void interaction_at(const nimbus_host_t *host, const nimbus_ray_t *ray, const nimbus_hit_t *hit, float time,
                    nimbus_interaction_t *out) {
  world_of(host).geometry->interaction(*ray, *hit, *out, time);
}

// The ray leaving ix along the unit direction d up to tfar, its origin offset to d's side.
nimbus_ray_t ray_leaving(const nimbus_interaction_t &ix, const Vec3f &d, float tfar) {
  nimbus_ray_t r;
  offset_origin(Vec3f::load(ix.p), Vec3f::load(ix.ng), ix.eps, d).store(r.org);
  d.store(r.dir);
  r.tnear = 0;
  r.tfar = tfar;
  r.mask = 0xFFFFFFFFu;
  r.flags = 0;
  return r;
}

// The shadow ray from ix to the point target.
nimbus_ray_t ray_towards(const nimbus_interaction_t &ix, const Vec3f &target) {
  const Vec3f to = target - Vec3f::load(ix.p);
  const Vec3f org = offset_origin(Vec3f::load(ix.p), Vec3f::load(ix.ng), ix.eps, to);
  const Vec3f d = target - org;
  const float dist = length(d);
  nimbus_ray_t r;
  (d / dist).store(r.dir);
  org.store(r.org);
  r.tnear = 0;
  // Light samples already lie off their emitter on this side (area_light.cpp), and point lights lie on no
  // surface: the ray stops a hair short of the target only so that the target itself is never counted.
  r.tfar = dist * (1 - 0x1p-20f);
  r.mask = 0xFFFFFFFFu;
  r.flags = 0;
  return r;
}

void spawn_ray(const nimbus_host_t *, const nimbus_interaction_t *ix, const float dir[3], float tfar,
               nimbus_ray_t *out) {
  *out = ray_leaving(*ix, Vec3f::load(dir), tfar);
}

void spawn_ray_to(const nimbus_host_t *, const nimbus_interaction_t *ix, const float p[3],
                  nimbus_ray_t *out) {
  *out = ray_towards(*ix, Vec3f::load(p));
}

void trace_from(const nimbus_host_t *host, const nimbus_thread_ctx_t *tc, const nimbus_interaction_t *from,
                const float dir[3], float time, nimbus_ray_t *ray, nimbus_hit_t *hit,
                nimbus_interaction_t *ix) {
  count_rays(run_of(host), tc, 1);
  const nimbus_ray_t r = ray_leaving(*from, Vec3f::load(dir), kInfinity);
  const GeometryScene &g = *world_of(host).geometry;
  g.intersect(r, *hit, time);
  if (ray) *ray = r;
  if (ix && hit->geom_id != NIMBUS_NONE) g.interaction(r, *hit, *ix, time);
}

uint8_t occluded_to(const nimbus_host_t *host, const nimbus_thread_ctx_t *tc, const nimbus_interaction_t *ix,
                    const float p[3], uint32_t to_infinity, float time) {
  count_rays(run_of(host), tc, 1);
  nimbus_ray_t r = ray_towards(*ix, Vec3f::load(p));
  if (to_infinity) r.tfar = kInfinity;
  return world_of(host).geometry->occluded(r, time) ? 1 : 0;
}

float bounding_sphere(const nimbus_host_t *host, float center[3]) {
  const GeometryScene &g = *world_of(host).geometry;
  g.sphere_center().store(center);
  return g.sphere_radius();
}

// Writes b as record `index` of out when it fits in `capacity`.
void write_bounds(const ObjectBounds &b, uint32_t index, nimbus_object_bounds_t *out, uint32_t capacity) {
  if (!out || index >= capacity) return;
  nimbus_object_bounds_t &o = out[index];
  b.lo.store(o.lo), b.hi.store(o.hi), b.sphere.center.store(o.center);
  o.radius = b.sphere.radius;
}

uint32_t sharp_bounds(const nimbus_host_t *host, float alpha_max, nimbus_object_bounds_t *out,
                      uint32_t capacity) {
  uint32_t count = 0;
  for (const SharpObject &o : world_of(host).sharp_objects)
    if (o.min_alpha < alpha_max) write_bounds(o.bounds, count++, out, capacity);
  return count;
}

uint32_t moving_bounds(const nimbus_host_t *host, nimbus_object_bounds_t *out, uint32_t capacity) {
  const std::vector<ObjectBounds> &moving = world_of(host).moving_objects;
  for (size_t i = 0; i < moving.size(); ++i) write_bounds(moving[i], uint32_t(i), out, capacity);
  return uint32_t(moving.size());
}

float generate_ray(const nimbus_host_t *host, const nimbus_camera_sample_t *sample, nimbus_ray_t *ray) {
  world_of(host).camera.generate_ray(*sample, *ray);
  return 1.0f;
}

float generate_ray_at(const nimbus_host_t *host, const nimbus_camera_sample_t *sample, float time,
                      nimbus_ray_t *ray) {
  world_of(host).camera.generate_ray_at(*sample, time, *ray);
  return 1.0f;
}

float connect_at(const nimbus_host_t *host, const float p[3], float time, const float lens_u[2],
                 float raster[2], float lens_point[3]) {
  Vec3f lp;
  const float w = world_of(host).camera.connect_at(Vec3f::load(p), time, lens_u, raster, lp);
  lp.store(lens_point);
  return w;
}

float resolution(const nimbus_host_t *host, uint32_t *width, uint32_t *height) {
  const Camera &c = world_of(host).camera;
  if (width) *width = c.width();
  if (height) *height = c.height();
  return c.pixel_angle();
}

float connect(const nimbus_host_t *host, const float p[3], const float lens_u[2], float raster[2],
              float lens_point[3]) {
  Vec3f lp;
  const float w = world_of(host).camera.connect(Vec3f::load(p), lens_u, raster, lp);
  lp.store(lens_point);
  return w;
}

float sample_film(const nimbus_host_t *host, uint32_t x, uint32_t y, const float u[2], float film[2]) {
  float weight = 0;
  const Vec2f d = world_of(host).filter.sample(u[0], u[1], weight);
  film[0] = float(x) + 0.5f + d.x;
  film[1] = float(y) + 0.5f + d.y;
  return weight;
}

uint32_t shutter(const nimbus_host_t *host, float *open, float *close) {
  const World &w = world_of(host);
  if (open) *open = w.shutter.open();
  if (close) *close = w.shutter.close();
  if (w.shutter.instantaneous()) return 0;
  return (w.geometry->moves() ? NIMBUS_MOTION_GEOMETRY : 0u) |
         (w.camera.moves() ? NIMBUS_MOTION_CAMERA : 0u) | (w.lights.moves() ? NIMBUS_MOTION_LIGHTS : 0u);
}

float sample_time(const nimbus_host_t *host, float u, float *pdf) {
  const Shutter &s = world_of(host).shutter;
  const float t = s.sample(u);
  if (pdf) *pdf = s.instantaneous() ? 1.0f : s.pdf(t);
  return t;
}

}  // namespace

const nimbus_host_scene_query_v1_t kSceneQueryV1 = {sizeof(nimbus_host_scene_query_v1_t),
                                                    intersect,
                                                    occluded,
                                                    interaction,
                                                    spawn_ray,
                                                    spawn_ray_to,
                                                    bounding_sphere,
                                                    sharp_bounds,
                                                    intersect_at,
                                                    occluded_at,
                                                    interaction_at,
                                                    moving_bounds,
                                                    trace_from,
                                                    occluded_to};

const nimbus_host_camera_v1_t kCameraV1 = {sizeof(nimbus_host_camera_v1_t),
                                           generate_ray,
                                           resolution,
                                           connect,
                                           sample_film,
                                           shutter,
                                           sample_time,
                                           generate_ray_at,
                                           connect_at};

}  // namespace nimbus
