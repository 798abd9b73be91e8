/* Nimbus SDK: the guiding plugin interface ("nimbus.iface.guiding" rev 1), e.g. a Metropolis photon
 * guide. Chains are partitioned by worker index, so no locks are needed. */
#ifndef NIMBUS_GUIDING_H
#define NIMBUS_GUIDING_H

#include "light_sampler.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct nimbus_guide_stats {
  uint32_t struct_size;
  uint32_t reserved;
  uint64_t paths_traced;
  uint64_t paths_visible;
} nimbus_guide_stats_t;

#define NIMBUS_IFACE_GUIDING "nimbus.iface.guiding"
typedef struct nimbus_guiding_v1 {
  uint32_t struct_size;
  /* [main-thread, !rendering] info borrowed. */
  nimbus_status_t (*prepare)(const nimbus_plugin_t *plugin, const nimbus_scene_info_t *info);
  /* [main-thread] */
  nimbus_status_t (*begin_iteration)(const nimbus_plugin_t *plugin, uint64_t iteration);
  /* [main-thread] Photon paths the guide wants traced in this iteration. */
  uint64_t (*budget)(const nimbus_plugin_t *plugin);
  /* [render-thread] Fills u (out, `dims` floats) with the primary-sample vector of photon path `path`. */
  void (*propose)(const nimbus_plugin_t *plugin, const nimbus_thread_ctx_t *ctx, uint64_t path, float *u,
                  uint32_t dims);
  /* [render-thread] Tells the guide whether path `path` reached an important region. */
  void (*report)(const nimbus_plugin_t *plugin, const nimbus_thread_ctx_t *ctx, uint64_t path,
                 int32_t visible);
  /* [main-thread] stats borrowed. */
  void (*end_iteration)(const nimbus_plugin_t *plugin, uint64_t iteration, const nimbus_guide_stats_t *stats);
} nimbus_guiding_v1_t;

#ifdef __cplusplus
}
#endif

#endif /* NIMBUS_GUIDING_H */
