/* Nimbus SDK: a plugin's learnt state across a resumed render ("nimbus.iface.render-state" rev 1, since
 * 1.4). Optional, for any plugin kind whose later iterations depend on what it learnt in earlier ones (an
 * adaptive photon budget, a guiding distribution). The host saves the state with every checkpoint, beside
 * the film's sums, and hands it back when the render resumes, so that a resumed render equals an
 * uninterrupted one bit for bit. The bytes are the plugin's own format: put a version tag in them. */
#ifndef NIMBUS_RENDER_STATE_H
#define NIMBUS_RENDER_STATE_H

#include "plugin.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Where a plugin writes its state during one save call. */
typedef struct nimbus_state_writer {
  uint32_t struct_size;
  uint32_t reserved;
  void *host_data; /* host-owned, opaque to the plugin */
  /* [main-thread] Appends `size` bytes (borrowed) to the state; writer (borrowed) is the one save was
   * given. NIMBUS_E_NO_MEMORY when the host cannot hold them; save then returns that status. */
  nimbus_status_t (*write)(const struct nimbus_state_writer *writer, const void *bytes, uint64_t size);
} nimbus_state_writer_t;

#define NIMBUS_IFACE_RENDER_STATE "nimbus.iface.render-state"
typedef struct nimbus_render_state_v1 {
  uint32_t struct_size;
  /* [main-thread] Between begin_render and end_render, with `iterations` iterations complete and the next
   * not begun: writes through `writer` (host-owned, borrowed for this call) what the plugin's later
   * iterations depend on that begin_render does not recompute. A failure costs the checkpoint, not the
   * render. */
  nimbus_status_t (*save)(const nimbus_plugin_t *plugin, uint64_t iterations,
                          const nimbus_state_writer_t *writer);
  /* [main-thread] When resuming, after begin_render (info.first_iteration is iterations + 1) and before
   * the first begin_iteration: `size` bytes (borrowed) that save wrote after `iterations` iterations, in
   * this process or an earlier one. Bytes it cannot read (another version's format, say) leave the state
   * begin_render made and return NIMBUS_E_VERSION or NIMBUS_E_INVALID_ARG: the host continues with a
   * warning, and the image stays consistent but is not the uninterrupted render's. */
  nimbus_status_t (*restore)(const nimbus_plugin_t *plugin, uint64_t iterations, const void *bytes,
                             uint64_t size);
} nimbus_render_state_v1_t;

#ifdef __cplusplus
}
#endif

#endif /* NIMBUS_RENDER_STATE_H */
