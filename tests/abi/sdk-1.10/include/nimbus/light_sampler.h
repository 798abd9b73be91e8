/* Nimbus SDK: the light-sampler plugin interface ("nimbus.iface.light-sampler" rev 1). A light sampler
 * decides which light next-event estimation and photon emission sample. Since 1.6 an integrator that
 * emits photons tells the sampler, before each photon pass, what its photons carry and which lights'
 * photons were used (update_emission), and the sampler's emitter table follows. */
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

/* Since 1.6. What an integrator that emits photons reports before a photon pass (update_emission). The
 * counts cover every earlier photon pass of the render, so the table is a function of this struct and
 * of what prepare saw: a resumed render rebuilds it without any sampler state. */
#define NIMBUS_S_TYPE_EMISSION_FEEDBACK 35u
#define NIMBUS_EMISSION_LIGHTMIX 1u /* LightMix is requested: every group's layer must converge */
typedef struct nimbus_emission_feedback {
  nimbus_struct_header_t header; /* s_type = NIMBUS_S_TYPE_EMISSION_FEEDBACK */
  uint32_t light_count;          /* length of the three arrays (the lights service's count) */
  uint32_t flags;                /* NIMBUS_EMISSION_* */
  float camera[3];               /* where the camera is (world space) */
  float reserved;
  /* Per light, borrowed: the flux the integrator's photons from it carry (0: it emits none, e.g. a
   * uniform environment; may differ from nimbus_light_info_t.power where the integrator prunes). */
  const double *photon_power;
  /* Per light, borrowed: uniform photon paths emitted from it so far; guided paths are not counted. */
  const uint64_t *emitted;
  /* Per light, borrowed: of those, the paths with a photon that a lookup used with non-zero light. */
  const uint64_t *contributed;
} nimbus_emission_feedback_t;

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
  /* Since 1.6 (absent from older samplers' tables: check NIMBUS_HAS_MEMBER), optional (may be NULL,
   * together with pmf_emitter). [main-thread, between-iterations] Rebuilds the table that pick_emitter
   * and pmf_emitter read from feedback (borrowed); they read it until the next call, so every photon of
   * a pass and every camera path that weighs them sees one table. Before the first call they pick by
   * emitted power. */
  nimbus_status_t (*update_emission)(const nimbus_plugin_t *plugin,
                                     const nimbus_emission_feedback_t *feedback);
  /* Since 1.6, optional (NULL exactly when update_emission is). [render-thread] The probability that
   * pick_emitter returns `light` (an integrator's camera side weighs photons by it): the rate at which
   * it really picks, 0 for a light it never picks. Such a light's caustics are left to path tracing, which
   * cannot reach a delta light behind glass, so a sampler keeps a defensive share for every light with
   * photon_power. */
  float (*pmf_emitter)(const nimbus_plugin_t *plugin, uint32_t light);
} nimbus_light_sampler_v1_t;

#ifdef __cplusplus
}
#endif

#endif /* NIMBUS_LIGHT_SAMPLER_H */
