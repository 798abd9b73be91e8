/* Nimbus SDK: the film (nimbus.host.film@1) and LightMix (nimbus.ext.lightmix@1).
 *
 * Elements are declared, not assumed: a plugin registers the elements it can produce during prepare;
 * the host allocates buffers only for those the scene or the command line requested. Each element
 * becomes the layer "<name>.R/G/B" of the multi-layer EXR; beauty is always present as R, G, B. */
#ifndef NIMBUS_FILM_H
#define NIMBUS_FILM_H

#include "host.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef int32_t nimbus_element_t;
#define NIMBUS_ELEMENT_BEAUTY 0 /* always registered and active */
#define NIMBUS_ELEMENT_INVALID (-1)

/* register_element flags */
#define NIMBUS_ELEMENT_AVERAGE 0u /* the value is averaged over samples (radiance, albedo, normal) */
#define NIMBUS_ELEMENT_SPLAT 1u   /* also receives splats (light tracing) */

#define NIMBUS_SERVICE_FILM "nimbus.host.film"
typedef struct nimbus_host_film_v1 {
  uint32_t struct_size;
  /* [main-thread, !rendering] Declares element `name` (borrowed, copied; [a-z0-9_.]+, dots separate
   * segments as in "lightmix.key") with `channels`
   * (1 or 3). Returns its id (>= 1), the id it already had, or NIMBUS_ELEMENT_INVALID. */
  nimbus_element_t (*register_element)(const nimbus_host_t *host, const char *name, uint32_t channels,
                                       uint32_t flags);
  /* [any-thread] Non-zero when `el` has a buffer (was requested). Skip work for inactive elements. */
  int32_t (*is_active)(const nimbus_host_t *host, nimbus_element_t el);
  /* [render-thread] Adds value (borrowed, `channels` floats) to pixel (x, y) of the tile being rendered
   * with `ctx`. Inactive elements ignore it. Beauty's sample count advances once per pixel and
   * iteration; other elements average over the same count. */
  void (*accumulate)(const nimbus_host_t *host, const nimbus_thread_ctx_t *ctx, nimbus_element_t el,
                     uint32_t x, uint32_t y, const float *value);
  /* [render-thread] Adds value (borrowed) at continuous raster position (fx, fy), any pixel, into
   * per-worker buffers merged after end_iteration. Like accumulated values, splats are divided by the
   * number of iterations at output: each iteration's splats must estimate the whole image once (a light
   * tracer tracing M paths per iteration splats contribution / M). Only elements registered with
   * NIMBUS_ELEMENT_SPLAT take splats ("beauty" may be re-registered with it). */
  void (*splat)(const nimbus_host_t *host, const nimbus_thread_ctx_t *ctx, nimbus_element_t el, float fx,
                float fy, const float *value);
} nimbus_host_film_v1_t;

/* ---- nimbus.ext.lightmix@1 --------------------------------------------------------------------- */
#define NIMBUS_EXT_LIGHTMIX "nimbus.ext.lightmix"
typedef struct nimbus_ext_lightmix_v1 {
  uint32_t struct_size;
  /* [any-thread] Non-zero when LightMix was requested. */
  int32_t (*is_active)(const nimbus_host_t *host);
  /* [any-thread] Number of light groups (nimbus_light_info_t.group < count). */
  uint32_t (*group_count)(const nimbus_host_t *host);
  /* [render-thread] Adds rgb value (borrowed) to group `group`'s layer at pixel (x, y) of the tile. */
  void (*accumulate)(const nimbus_host_t *host, const nimbus_thread_ctx_t *ctx, uint32_t group, uint32_t x,
                     uint32_t y, const float value[3]);
  /* [render-thread] Splats rgb value (borrowed) into group `group`'s layer (see film splat). */
  void (*splat)(const nimbus_host_t *host, const nimbus_thread_ctx_t *ctx, uint32_t group, float fx, float fy,
                const float value[3]);
} nimbus_ext_lightmix_v1_t;

#ifdef __cplusplus
}
#endif

#endif /* NIMBUS_FILM_H */
