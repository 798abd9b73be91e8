/* Nimbus SDK: the host's emitters (nimbus.host.lights@1). Which light to sample is the light sampler's
 * choice (light_sampler.h); this service samples and evaluates a given light.
 *
 * pdfs of incident samples are solid-angle densities at the receiving point, excluding the light
 * selection probability. For delta lights (point, spot, directional) pdf is 1 and the sample carries
 * NIMBUS_LIGHT_DELTA_* flags. */
#ifndef NIMBUS_LIGHTS_H
#define NIMBUS_LIGHTS_H

#include "scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Light flags (info and samples). */
#define NIMBUS_LIGHT_DELTA_POSITION 1u  /* point, spot */
#define NIMBUS_LIGHT_DELTA_DIRECTION 2u /* directional */
#define NIMBUS_LIGHT_INFINITE 4u        /* environment, sun: at infinity, found by missed rays */
#define NIMBUS_LIGHT_AREA 8u            /* emissive geometry, found by hitting it */
#define NIMBUS_LIGHT_TWO_SIDED 16u      /* since 1.1: area light emitting from both sides of its surface */

#define NIMBUS_S_TYPE_LIGHT_INFO 16u
typedef struct nimbus_light_info {
  nimbus_struct_header_t header; /* s_type = NIMBUS_S_TYPE_LIGHT_INFO; caller zero-fills and sets size */
  uint32_t flags;
  uint32_t group;      /* LightMix group index */
  float power;         /* emitted flux, luminance of W (infinite lights: through the scene's disk) */
  float bounds_min[3]; /* world bounds of the emitter (infinite lights: the scene bounds) */
  float bounds_max[3];
  float axis[3];     /* main emission direction (area, spot, sun); zero if none */
  float cos_theta_o; /* cone of normals around axis: cos of half angle (-1: all directions) */
  float cos_theta_e; /* emission spread beyond the normal cone: cos (0: hemisphere per normal) */
} nimbus_light_info_t;

typedef struct nimbus_light_incident {
  float wi[3];    /* unit direction from the receiver towards the light */
  float dist;     /* distance to the light point (INFINITY for infinite lights) */
  float p[3];     /* light point for spawn_ray_to: area lights offset it off the emitter on the receiver's
                   * side by its rounding error (dist is to the surface); infinite lights: a point far away */
  float n[3];     /* light surface normal at p (zero for point and infinite lights) */
  float L[3];     /* incident radiance (area, infinite) or intensity / dist^2 (delta lights) */
  float pdf;      /* solid-angle pdf of wi (1 for delta lights); 0 = no sample */
  uint32_t flags; /* light flags */
  uint32_t reserved;
} nimbus_light_incident_t;

typedef struct nimbus_light_emission {
  float org[3];  /* photon origin */
  float dir[3];  /* photon direction */
  float n[3];    /* surface normal at org (zero for point lights; the direction for infinite lights) */
  float Le[3];   /* emitted radiance (or intensity) along dir */
  float pdf_pos; /* area pdf of org (1 for delta positions; 1/(pi R^2) for infinite lights) */
  float pdf_dir; /* solid-angle pdf of dir (1 for delta directions) */
  uint32_t flags;
  uint32_t reserved;
} nimbus_light_emission_t;

#define NIMBUS_SERVICE_LIGHTS "nimbus.host.lights"
typedef struct nimbus_host_lights_v1 {
  uint32_t struct_size;
  /* [any-thread] Number of lights (emissive shapes count one each). */
  uint32_t (*count)(const nimbus_host_t *host);
  /* [any-thread] Fills info (out; caller sets header.struct_size) for light i. */
  nimbus_status_t (*info)(const nimbus_host_t *host, uint32_t light, nimbus_light_info_t *info);
  /* [render-thread] Samples light `light` as seen from ix with two uniform numbers u. ix, u borrowed;
   * out caller storage. */
  void (*sample_incident)(const nimbus_host_t *host, uint32_t light, const nimbus_interaction_t *ix,
                          const float u[2], nimbus_light_incident_t *out);
  /* [render-thread] Solid-angle pdf that sample_incident from `ref` produces direction wi hitting the
   * light at `on_light` (borrowed; NULL for infinite lights). 0 for delta lights. */
  float (*pdf_incident)(const nimbus_host_t *host, uint32_t light, const nimbus_interaction_t *ref,
                        const float wi[3], const nimbus_interaction_t *on_light);
  /* [render-thread] Radiance L (out, rgb) leaving the emissive surface point on_light towards wo.
   * on_light, wo borrowed. */
  void (*eval_emitted)(const nimbus_host_t *host, const nimbus_interaction_t *on_light, const float wo[3],
                       float L[3]);
  /* [render-thread] Radiance L (out, rgb) that infinite light `light` sends along -dir (dir borrowed: the
   * direction of the ray that escaped the scene). Zero for other lights. */
  void (*eval_infinite)(const nimbus_host_t *host, uint32_t light, const float dir[3], float L[3]);
  /* [render-thread] Samples a photon leaving `light` with four uniform numbers u (borrowed). out caller
   * storage; out->pdf_pos = 0 on failure. */
  void (*sample_emission)(const nimbus_host_t *host, uint32_t light, const float u[4],
                          nimbus_light_emission_t *out);
} nimbus_host_lights_v1_t;

#ifdef __cplusplus
}
#endif

#endif /* NIMBUS_LIGHTS_H */
