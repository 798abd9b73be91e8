// The service tables (defined one file per service in abi/*_service.cpp): 1.0's, and the spectral
// service of 1.7.
#pragma once

#include <nimbus/nimbus.h>

namespace nimbus {

extern const nimbus_host_scene_query_v1_t kSceneQueryV1;
extern const nimbus_host_camera_v1_t kCameraV1;
extern const nimbus_host_bsdf_v1_t kBsdfV1;
extern const nimbus_host_lights_v1_t kLightsV1;
extern const nimbus_host_film_v1_t kFilmV1;
extern const nimbus_ext_lightmix_v1_t kLightMixV1;
extern const nimbus_host_rng_v1_t kRngV1;
extern const nimbus_host_progress_v1_t kProgressV1;
extern const nimbus_host_tasks_v1_t kTasksV1;
extern const nimbus_host_memory_v1_t kMemoryV1;
extern const nimbus_host_thread_check_v1_t kThreadCheckV1;
extern const nimbus_host_spectral_v1_t kSpectralV1;

}  // namespace nimbus
