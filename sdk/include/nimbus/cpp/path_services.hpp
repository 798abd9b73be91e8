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

// The services of PathServices as a descriptor's required_services list.
#define NIMBUS_CAMERA_PATH_SERVICES                                                                  \
  "nimbus.host.scene-query@1", "nimbus.host.camera@1", "nimbus.host.bsdf@1", "nimbus.host.lights@1", \
      "nimbus.host.film@1", "nimbus.host.rng@1"

}  // namespace nimbus::sdk
