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
#define NIMBUS_LIGHT_MOVES                                                  \
  32u /* since 1.7 (info only): moves while the shutter is open; the bounds \
       * and cone cover its whole sweep, and the _at members place it */

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
  /* Since 1.2: total emitting surface area (area lights; 0 for other lights). Written only when the
   * caller's header.struct_size covers it; hosts before 1.2 leave it as the caller zero-filled it. */
  float area;
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
  /* Since 1.2 (absent from a 1.1 host's table: check NIMBUS_HAS_MEMBER before calling).
   * [any-thread] What light `light` emits from point p on it along the unit direction dir, as
   * sample_emission reports it in Le: radiance for area lights (p on the surface, n its normal there
   * as sample_emission's out->n or a hit's ng; zero towards the back of a one-sided light), intensity
   * for point and spot lights (with the spot's falloff), the radiance travelling along dir for infinite
   * lights (a sun of zero diameter: its value along its own direction, whatever dir). p, n, dir
   * borrowed (n and p are read for area lights only and may be NULL for others); Le out (rgb). An area
   * light without n, or an unknown light, emits zero. */
  void (*eval_emission)(const nimbus_host_t *host, uint32_t light, const float p[3], const float n[3],
                        const float dir[3], float Le[3]);
  /* Since 1.2 (absent from a 1.1 host's table: check NIMBUS_HAS_MEMBER before calling).
   * [any-thread] The densities with which sample_emission of `light` produces a photon leaving p along
   * the unit direction dir, exactly as it reports them. pdf_pos (out): the area density of p (1 for
   * delta positions; infinite lights: 1/(pi R^2) of their emission disk, whatever p). pdf_dir (out): the
   * solid-angle density of dir given p (1 for delta directions; 0 where the light never emits). p, n,
   * dir borrowed, as for eval_emission. An area light without n has pdf_dir 0; an unknown light, both 0. */
  void (*pdf_emission)(const nimbus_host_t *host, uint32_t light, const float p[3], const float n[3],
                       const float dir[3], float *pdf_pos, float *pdf_dir);
  /* Since 1.7 (absent from older hosts' tables: check NIMBUS_HAS_MEMBER before calling). Point and spot
   * lights may move over the shutter (the camera service's shutter() reports NIMBUS_MOTION_LIGHTS); these
   * are the four members above with the light where it is at scene time `time`, and the same results
   * when it holds still. Arguments, ownership and out-records as theirs. */
  /* [render-thread] sample_incident at scene time `time`. ix, u borrowed; out caller storage. */
  void (*sample_incident_at)(const nimbus_host_t *host, uint32_t light, const nimbus_interaction_t *ix,
                             const float u[2], float time, nimbus_light_incident_t *out);
  /* [render-thread] sample_emission at scene time `time`. u borrowed; out caller storage. */
  void (*sample_emission_at)(const nimbus_host_t *host, uint32_t light, const float u[4], float time,
                             nimbus_light_emission_t *out);
  /* [any-thread] eval_emission at scene time `time`. p, n, dir borrowed; Le out. */
  void (*eval_emission_at)(const nimbus_host_t *host, uint32_t light, const float p[3], const float n[3],
                           const float dir[3], float time, float Le[3]);
  /* [any-thread] pdf_emission at scene time `time`. p, n, dir borrowed; pdf_pos, pdf_dir out. */
  void (*pdf_emission_at)(const nimbus_host_t *host, uint32_t light, const float p[3], const float n[3],
                          const float dir[3], float time, float *pdf_pos, float *pdf_dir);
} nimbus_host_lights_v1_t;

#ifdef __cplusplus
}
#endif

#endif /* NIMBUS_LIGHTS_H */
