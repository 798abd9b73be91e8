// The host services a camera-path integrator calls, fetched once in init. Requires C++17.
#pragma once

#include <nimbus/nimbus.hpp>

namespace nimbus::sdk {

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
// (SDK 1.7), else through the timeless queries, so that a static scene runs exactly as before.
struct TimedScene {
  const nimbus_host_scene_query_v1_t *scene = nullptr;
  bool timed = false;

  // [main-thread] Whether paths need a time: the host has the 1.7 queries and something moves.
  static bool needed(const nimbus_host_t *h, const nimbus_host_scene_query_v1_t *scene,
                     const nimbus_host_camera_v1_t *camera) {
    return NIMBUS_HAS_MEMBER(camera, nimbus_host_camera_v1_t, sample_time) &&
           NIMBUS_HAS_MEMBER(scene, nimbus_host_scene_query_v1_t, interaction_at) &&
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
  void interaction(const nimbus_host_t *h, const nimbus_ray_t &ray, const nimbus_hit_t &hit, float time,
                   nimbus_interaction_t &ix) const {
    if (timed)
      scene->interaction_at(h, &ray, &hit, time, &ix);
    else
      scene->interaction(h, &ray, &hit, &ix);
  }
};

// The services of PathServices as a descriptor's required_services list.
#define NIMBUS_CAMERA_PATH_SERVICES                                                                  \
  "nimbus.host.scene-query@1", "nimbus.host.camera@1", "nimbus.host.bsdf@1", "nimbus.host.lights@1", \
      "nimbus.host.film@1", "nimbus.host.rng@1"

}  // namespace nimbus::sdk
