/* Nimbus SDK: the light-sampler plugin interface ("nimbus.iface.light-sampler" rev 1). A light sampler
 * decides which light next-event estimation (and photon emission) samples. */
#ifndef NIMBUS_LIGHT_SAMPLER_H
#define NIMBUS_LIGHT_SAMPLER_H

#include "plugin.h"
#include "scene.h"

#ifdef __cplusplus
extern "C" {
#endif

#define NIMBUS_S_TYPE_SCENE_INFO 32u
typedef struct nimbus_scene_info {
  nimbus_struct_header_t header; /* s_type = NIMBUS_S_TYPE_SCENE_INFO */
  uint32_t light_count;
  uint32_t worker_count;
  float scene_center[3];
  float scene_radius;
} nimbus_scene_info_t;

#define NIMBUS_IFACE_LIGHT_SAMPLER "nimbus.iface.light-sampler"
typedef struct nimbus_light_sampler_v1 {
  uint32_t struct_size;
  /* [main-thread, !rendering] Builds tables from the host's lights service. info borrowed. */
  nimbus_status_t (*prepare)(const nimbus_plugin_t *plugin, const nimbus_scene_info_t *info);
  /* [render-thread] Picks a light for NEE at ix (borrowed) with u in [0,1); *pmf (out) its probability.
   * Returns NIMBUS_NONE when no light can contribute. */
  uint32_t (*pick)(const nimbus_plugin_t *plugin, const nimbus_interaction_t *ix, float u, float *pmf);
  /* [render-thread] Probability that pick at ix (borrowed) returns `light` (for MIS). */
  float (*pmf)(const nimbus_plugin_t *plugin, const nimbus_interaction_t *ix, uint32_t light);
  /* [render-thread] Picks a light to emit a photon from with u in [0,1), independent of any receiver;
   * *pmf (out) its probability. */
  uint32_t (*pick_emitter)(const nimbus_plugin_t *plugin, float u, float *pmf);
  /* [render-thread] Optional (may be NULL): reports the contribution v of a sample of `light`. The SDK
   * kit's camera-path layer (nimbus/cpp/camera_path.hpp) reports every next-event sample it picked: v
   * is the luminance of path throughput x BSDF x cos x L / (the light's own pdf), before the selection
   * probability and MIS; 0 when the sample is occluded or carries no light. Called concurrently from
   * every render thread (ctx->worker tells them apart, ctx borrowed); a sampler that adapts keeps
   * per-worker data and merges it in end_iteration in an order that does not depend on the threads. */
  void (*record)(const nimbus_plugin_t *plugin, const nimbus_thread_ctx_t *ctx, uint32_t light, float v);
  /* [main-thread] Optional (may be NULL): adapt tables between iterations; the host calls it after
   * every iteration's camera pass, before the integrator's end_iteration. */
  void (*end_iteration)(const nimbus_plugin_t *plugin, uint64_t iteration);
} nimbus_light_sampler_v1_t;

#ifdef __cplusplus
}
#endif

#endif /* NIMBUS_LIGHT_SAMPLER_H */
