// The host services a camera-path integrator calls, fetched once in init. Requires C++17.
#pragma once

#include <nimbus/nimbus.hpp>

#include <nimbus/cpp/math.hpp>

namespace nimbus::sdk {

// The ray a light path leaves its emitter by (`flags`: the emission sample's): off an area light's surface
// by relative_offset, since emission points carry no error bound; from a point or a disk as it is.
inline nimbus_ray_t emission_ray(const Vec3f &org, const Vec3f &dir, uint32_t flags) {
  nimbus_ray_t ray;
  org.store(ray.org);
  dir.store(ray.dir);
  ray.tnear = (flags & NIMBUS_LIGHT_AREA) ? relative_offset(org) : 0;
  ray.tfar = kInfinity;
  ray.mask = ~0u, ray.flags = 0;
  return ray;
}

struct PathServices {
  const nimbus_host_scene_query_v1_t *scene = nullptr;
  const nimbus_host_camera_v1_t *camera = nullptr;
  const nimbus_host_bsdf_v1_t *bsdf = nullptr;
  const nimbus_host_lights_v1_t *lights = nullptr;
  const nimbus_host_film_v1_t *film = nullptr;
  const nimbus_host_rng_v1_t *rng = nullptr;
  const nimbus_ext_lightmix_v1_t *lightmix = nullptr;  // optional: NULL on hosts without LightMix

  // [main-thread] True when every required service is there (the camera with sample_film, SDK 1.1).
  bool fetch(const Host &host) {
    scene = host.service<nimbus_host_scene_query_v1_t>(NIMBUS_SERVICE_SCENE_QUERY);
    camera = host.service<nimbus_host_camera_v1_t>(NIMBUS_SERVICE_CAMERA);
    bsdf = host.service<nimbus_host_bsdf_v1_t>(NIMBUS_SERVICE_BSDF);
    lights = host.service<nimbus_host_lights_v1_t>(NIMBUS_SERVICE_LIGHTS);
    film = host.service<nimbus_host_film_v1_t>(NIMBUS_SERVICE_FILM);
    rng = host.service<nimbus_host_rng_v1_t>(NIMBUS_SERVICE_RNG);
    lightmix = host.service<nimbus_ext_lightmix_v1_t>(NIMBUS_EXT_LIGHTMIX);
    return scene && camera && bsdf && lights && film && rng &&
           NIMBUS_HAS_MEMBER(camera, nimbus_host_camera_v1_t, sample_film);
  }
};

// The scene as a path sees it: at the path's scene time when something moves while the shutter is open
// (SDK 1.7), else through the timeless queries, so that a static scene runs exactly as before. Camera and
// lights are part of it: either may move too.
struct TimedScene {
  const nimbus_host_scene_query_v1_t *scene = nullptr;
  const nimbus_host_camera_v1_t *camera = nullptr;
  const nimbus_host_lights_v1_t *lights = nullptr;
  bool timed = false;
  bool fused = false;  // the host spawns and traces a ray in one call (SDK 1.10)

  // [main-thread] The timed view when the host has the 1.7 members and something moves, else timeless.
  static TimedScene of(const nimbus_host_t *h, const nimbus_host_scene_query_v1_t *scene,
                       const nimbus_host_camera_v1_t *camera, const nimbus_host_lights_v1_t *lights) {
    return {scene, camera, lights, needed(h, scene, camera, lights),
            NIMBUS_HAS_MEMBER(scene, nimbus_host_scene_query_v1_t, occluded_to)};
  }
  // [main-thread] Whether paths need a time: the host has the 1.7 members and something moves.
  static bool needed(const nimbus_host_t *h, const nimbus_host_scene_query_v1_t *scene,
                     const nimbus_host_camera_v1_t *camera, const nimbus_host_lights_v1_t *lights) {
    return NIMBUS_HAS_MEMBER(camera, nimbus_host_camera_v1_t, connect_at) &&
           NIMBUS_HAS_MEMBER(scene, nimbus_host_scene_query_v1_t, interaction_at) &&
           NIMBUS_HAS_MEMBER(lights, nimbus_host_lights_v1_t, pdf_emission_at) &&
           camera->shutter(h, nullptr, nullptr) != 0;
  }
  // [render-thread] One ray each; ray, hit and ix as the scene query's.
  void intersect(const nimbus_host_t *h, const nimbus_thread_ctx_t &ctx, const nimbus_ray_t &ray, float time,
                 nimbus_hit_t &hit) const {
    if (timed)
      scene->intersect_at(h, &ctx, &ray, &time, &hit, 1);
    else
      scene->intersect(h, &ctx, &ray, &hit, 1);
  }
  bool occluded(const nimbus_host_t *h, const nimbus_thread_ctx_t &ctx, const nimbus_ray_t &ray,
                float time) const {
    uint8_t blocked = 0;
    if (timed)
      scene->occluded_at(h, &ctx, &ray, &time, &blocked, 1);
    else
      scene->occluded(h, &ctx, &ray, &blocked, 1);
    return blocked != 0;
  }
  // [render-thread] The closest hit (out) of `ray` and, for a hit, its interaction (out).
  void trace(const nimbus_host_t *h, const nimbus_thread_ctx_t &ctx, const nimbus_ray_t &ray, float time,
             nimbus_hit_t &hit, nimbus_interaction_t &ix) const {
    intersect(h, ctx, ray, time, hit);
    if (hit.geom_id != NIMBUS_NONE) interaction(h, ray, hit, time, ix);
  }
  // [render-thread] trace of the ray leaving `from` along the unit direction dir; ix may be `from`
  // itself.
  void trace_from(const nimbus_host_t *h, const nimbus_thread_ctx_t &ctx, const nimbus_interaction_t &from,
                  const float dir[3], float time, nimbus_hit_t &hit, nimbus_interaction_t &ix) const {
    if (fused) return scene->trace_from(h, &ctx, &from, dir, time, nullptr, &hit, &ix);
    nimbus_ray_t ray;
    scene->spawn_ray(h, &from, dir, kInfinity, &ray);
    trace(h, ctx, ray, time, hit, ix);
  }
  // [render-thread] Whether the segment from ix to p is blocked (past p too when to_infinity).
  bool occluded_to(const nimbus_host_t *h, const nimbus_thread_ctx_t &ctx, const nimbus_interaction_t &ix,
                   const float p[3], bool to_infinity, float time) const {
    if (fused) return scene->occluded_to(h, &ctx, &ix, p, to_infinity ? 1 : 0, time) != 0;
    nimbus_ray_t shadow;
    scene->spawn_ray_to(h, &ix, p, &shadow);
    if (to_infinity) shadow.tfar = kInfinity;
    return occluded(h, ctx, shadow, time);
  }
  void interaction(const nimbus_host_t *h, const nimbus_ray_t &ray, const nimbus_hit_t &hit, float time,
                   nimbus_interaction_t &ix) const {
    if (timed)
      scene->interaction_at(h, &ray, &hit, time, &ix);
    else
      scene->interaction(h, &ray, &hit, &ix);
  }
  // [any-thread] The scene time that u in [0, 1) maps to on the shutter's curve, whose density the film
  // integrates over (a path drawn so keeps weight 1); 0 when nothing moves.
  float time(const nimbus_host_t *h, float u) const {
    return timed ? camera->sample_time(h, u, nullptr) : 0.0f;
  }
  // [any-thread] The camera's generate_ray and connect at `time`.
  float generate_ray(const nimbus_host_t *h, const nimbus_camera_sample_t &cs, float time,
                     nimbus_ray_t &ray) const {
    return timed ? camera->generate_ray_at(h, &cs, time, &ray) : camera->generate_ray(h, &cs, &ray);
  }
  float connect(const nimbus_host_t *h, const float p[3], float time, const float lens_u[2], float raster[2],
                float lens_point[3]) const {
    return timed ? camera->connect_at(h, p, time, lens_u, raster, lens_point)
                 : camera->connect(h, p, lens_u, raster, lens_point);
  }
  // [render-thread] The lights service's sampling at `time` (a moving light where it is then).
  void sample_incident(const nimbus_host_t *h, uint32_t light, const nimbus_interaction_t &ix,
                       const float u[2], float time, nimbus_light_incident_t &out) const {
    if (timed)
      lights->sample_incident_at(h, light, &ix, u, time, &out);
    else
      lights->sample_incident(h, light, &ix, u, &out);
  }
  void sample_emission(const nimbus_host_t *h, uint32_t light, const float u[4], float time,
                       nimbus_light_emission_t &out) const {
    if (timed)
      lights->sample_emission_at(h, light, u, time, &out);
    else
      lights->sample_emission(h, light, u, &out);
  }
  // [any-thread] eval_emission and pdf_emission at `time`.
  void eval_emission(const nimbus_host_t *h, uint32_t light, const float p[3], const float n[3],
                     const float dir[3], float time, float Le[3]) const {
    if (timed)
      lights->eval_emission_at(h, light, p, n, dir, time, Le);
    else
      lights->eval_emission(h, light, p, n, dir, Le);
  }
  void pdf_emission(const nimbus_host_t *h, uint32_t light, const float p[3], const float n[3],
                    const float dir[3], float time, float &pdf_pos, float &pdf_dir) const {
    if (timed)
      lights->pdf_emission_at(h, light, p, n, dir, time, &pdf_pos, &pdf_dir);
    else
      lights->pdf_emission(h, light, p, n, dir, &pdf_pos, &pdf_dir);
  }
};

// The services of PathServices as a descriptor's required_services list.
#define NIMBUS_CAMERA_PATH_SERVICES                                                                  \
  "nimbus.host.scene-query@1", "nimbus.host.camera@1", "nimbus.host.bsdf@1", "nimbus.host.lights@1", \
      "nimbus.host.film@1", "nimbus.host.rng@1"

}  // namespace nimbus::sdk
