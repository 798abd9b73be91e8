/* Nimbus SDK: the integrator plugin interface ("nimbus.iface.integrator" rev 1).
 *
 * The host drives one progressive loop: iteration i renders one sample per pixel of every pixel.
 *   prepare → begin_render → for each iteration: begin_iteration, render_tile (parallel, disjoint tiles),
 *   end_iteration → end_render.
 * Between begin_iteration returning and end_iteration starting, shared plugin state is read-only. */
#ifndef NIMBUS_INTEGRATOR_H
#define NIMBUS_INTEGRATOR_H

#include "guiding.h"
#include "light_sampler.h"

#ifdef __cplusplus
extern "C" {
#endif

/* An option meant for the integrator, e.g. {"caustics", "on"}. key and value: host-owned until
 * end_render. Since 1.2, for a plugin that declares options (nimbus_option_list_t), the host passes each
 * declared option once, validated, with the scene's or command line's value or else the default. */
typedef struct nimbus_option {
  const char *key;
  const char *value;
} nimbus_option_t;

#define NIMBUS_S_TYPE_RENDER_SETUP 64u
typedef struct nimbus_render_setup {
  nimbus_struct_header_t header; /* s_type = NIMBUS_S_TYPE_RENDER_SETUP */
  uint32_t width, height;        /* full image */
  uint32_t max_depth;            /* path length in segments: a camera ray hitting a light is 1 */
  uint32_t option_count;
  uint64_t seed;
  const nimbus_option_t *options; /* host-owned until end_render; option_count entries */
  /* The light sampler bound for this render (never NULL) and an optional guide (may be NULL). The
   * plugins and tables are host-owned until end_render; call them per the tags of their headers.
   * Since 1.5 the host binds the guide the scene names (render.guide, --guide) or else the one the
   * integrator's descriptor names with the feature "default-guide=<id>", and calls its prepare. An
   * integrator that drives "nimbus.iface.guiding" rev 2 fetches it through guide->get_interface;
   * guide_iface is the guide's rev 1 table, or NULL when it has none. */
  const nimbus_plugin_t *light_sampler;
  const nimbus_light_sampler_v1_t *light_sampler_iface; /* host-owned until end_render */
  const nimbus_plugin_t *guide;                         /* host-owned until end_render; may be NULL */
  const nimbus_guiding_v1_t *guide_iface;               /* host-owned until end_render; NULL without guide */
} nimbus_render_setup_t;

#define NIMBUS_S_TYPE_RENDER_INFO 65u
typedef struct nimbus_render_info {
  nimbus_struct_header_t header; /* s_type = NIMBUS_S_TYPE_RENDER_INFO */
  uint32_t worker_count;         /* bound of nimbus_thread_ctx_t.worker_index */
  uint32_t reserved;
  uint64_t first_iteration;    /* 1, or later when resuming */
  uint64_t planned_iterations; /* 0 when the render stops by time or error instead */
  /* Since 1.8 (check header.struct_size). This render is task `task_index` of `task_count` processes that
   * share one frame's iterations (nimbus render --task K --tasks N, joined by nimbus merge): it renders the
   * iterations task_index + 1 + k * task_count, k = 0, 1, ... Iteration numbers everywhere (first_iteration,
   * begin_iteration, tile.iteration) are these frame-wide indices; planned_iterations counts this task's
   * own. A whole render is task 0 of 1. A plugin that numbers something of its own per render (photon
   * passes j = 1, 2, ...) and keys random numbers or schedules by it uses the frame-wide number
   * task_index + 1 + (j - 1) * task_count, so tasks never share random numbers and follow one schedule. */
  uint32_t task_index;
  uint32_t task_count;
} nimbus_render_info_t;

/* Pixels [x0, x1) × [y0, y1) of iteration `iteration` (1-based). */
typedef struct nimbus_tile {
  uint32_t x0, y0, x1, y1;
  uint64_t iteration;
} nimbus_tile_t;

#define NIMBUS_IFACE_INTEGRATOR "nimbus.iface.integrator"
typedef struct nimbus_integrator_v1 {
  uint32_t struct_size;
  /* [main-thread, !rendering] Register film elements, fetch services, bind sampler and guide. setup
   * borrowed (pointers inside it live until end_render). */
  nimbus_status_t (*prepare)(const nimbus_plugin_t *plugin, const nimbus_render_setup_t *setup);
  /* [main-thread] Allocate per-worker state. info borrowed. */
  nimbus_status_t (*begin_render)(const nimbus_plugin_t *plugin, const nimbus_render_info_t *info);
  /* [main-thread] May run tasks.parallel_for (photon passes). */
  nimbus_status_t (*begin_iteration)(const nimbus_plugin_t *plugin, uint64_t iteration);
  /* [render-thread] Many at once, disjoint tiles. ctx, tile borrowed. */
  nimbus_status_t (*render_tile)(const nimbus_plugin_t *plugin, const nimbus_thread_ctx_t *ctx,
                                 const nimbus_tile_t *tile);
  /* [main-thread] After all tiles and splats of the iteration. */
  nimbus_status_t (*end_iteration)(const nimbus_plugin_t *plugin, uint64_t iteration);
  /* [main-thread] `reason`: NIMBUS_OK, NIMBUS_E_CANCELLED or the failure that ended the render. */
  void (*end_render)(const nimbus_plugin_t *plugin, nimbus_status_t reason);
} nimbus_integrator_v1_t;

#ifdef __cplusplus
}
#endif

#endif /* NIMBUS_INTEGRATOR_H */
