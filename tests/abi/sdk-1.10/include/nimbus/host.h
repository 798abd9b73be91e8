/* Nimbus SDK: the host as a plugin sees it, per-callback thread context, and the small core services
 * (memory, progress, tasks, thread-check). Other services have a header each. */
#ifndef NIMBUS_HOST_H
#define NIMBUS_HOST_H

#include "version.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef int32_t nimbus_log_level_t;
#define NIMBUS_LOG_DEBUG 0
#define NIMBUS_LOG_INFO 1
#define NIMBUS_LOG_WARNING 2
#define NIMBUS_LOG_ERROR 3

typedef struct nimbus_host {
  uint32_t struct_size;
  nimbus_version_t abi; /* the SDK version of the host */
  void *host_data;      /* host-owned, opaque */
  /* [any-thread] Service table `id` (borrowed) at revision `rev`, or NULL when the host lacks it. The
   * same pointer every time; host-owned until the host is destroyed. */
  const void *(*get_service)(const struct nimbus_host *host, const char *id, uint32_t rev);
  /* [any-thread] Logs `msg` (borrowed, copied) on behalf of `plugin_id` (borrowed, may be NULL). */
  void (*log)(const struct nimbus_host *host, nimbus_log_level_t level, const char *plugin_id,
              const char *msg);
} nimbus_host_t;

/* Per-callback context of a worker. Host-owned; borrowed for one callback. `scratch` may be reused by
 * the plugin during that callback only; its content is not preserved across callbacks. */
typedef struct nimbus_thread_ctx {
  uint32_t struct_size;
  uint32_t worker_index; /* < worker_count; index per-worker state with it, never use thread_local */
  uint32_t worker_count;
  uint32_t reserved;
  void *scratch; /* host-owned, borrowed for the callback */
  size_t scratch_bytes;
} nimbus_thread_ctx_t;

/* ---- nimbus.host.memory@1: allocations the host reads or frees later ---------------------------- */
#define NIMBUS_SERVICE_MEMORY "nimbus.host.memory"
typedef struct nimbus_host_memory_v1 {
  uint32_t struct_size;
  /* [any-thread] Host-owned block of `bytes`, aligned to `alignment` (power of two, <= 4096); NULL on
   * failure. Free with `free` of this table only. */
  void *(*alloc)(const nimbus_host_t *host, size_t bytes, size_t alignment);
  /* [any-thread] Frees block (host-owned until this call; from `alloc` of this table); NULL is ignored. */
  void (*free)(const nimbus_host_t *host, void *block);
} nimbus_host_memory_v1_t;

/* ---- nimbus.host.progress@1 -------------------------------------------------------------------- */
#define NIMBUS_SERVICE_PROGRESS "nimbus.host.progress"
typedef struct nimbus_host_progress_v1 {
  uint32_t struct_size;
  /* [any-thread] Reports progress of a phase (borrowed name, e.g. "photons") the plugin runs inside an
   * iteration hook; the host shows it next to the iteration count. */
  void (*report)(const nimbus_host_t *host, uint64_t done, uint64_t total, const char *phase);
  /* [any-thread] Non-zero once the user asked to stop (Ctrl-C, time budget). Long hooks poll it. */
  int32_t (*cancelled)(const nimbus_host_t *host);
  /* [any-thread] Adds `value` to the named counter (borrowed name), shown in statistics and written
   * into the EXR metadata as nimbus:stat:<name>. */
  void (*stat_add)(const nimbus_host_t *host, const char *counter, double value);
} nimbus_host_progress_v1_t;

/* ---- nimbus.host.tasks@1: parallel work on the host's worker arena -------------------------------- */
#define NIMBUS_SERVICE_TASKS "nimbus.host.tasks"
/* [render-thread] Processes items [begin, end). `user` borrowed from the parallel_for call. */
typedef void (*nimbus_task_fn)(const nimbus_thread_ctx_t *ctx, uint64_t begin, uint64_t end, void *user);
typedef struct nimbus_host_tasks_v1 {
  uint32_t struct_size;
  uint32_t reserved;
  /* [main-thread] Runs fn over [0, count) in chunks of at most `grain` items and returns when all are
   * done. Chunk boundaries depend only on count and grain, never on the thread count. user is borrowed:
   * passed to every fn call unchanged, never dereferenced by the host. */
  nimbus_status_t (*parallel_for)(const nimbus_host_t *host, uint64_t count, uint64_t grain,
                                  nimbus_task_fn fn, void *user);
  /* [any-thread] Number of workers: the bound of nimbus_thread_ctx_t.worker_index. */
  uint32_t (*worker_count)(const nimbus_host_t *host);
} nimbus_host_tasks_v1_t;

/* ---- nimbus.host.thread-check@1 ----------------------------------------------------------------- */
#define NIMBUS_SERVICE_THREAD_CHECK "nimbus.host.thread-check"
typedef struct nimbus_host_thread_check_v1 {
  uint32_t struct_size;
  /* [any-thread] Non-zero on the thread that drives the progressive loop. */
  int32_t (*is_main_thread)(const nimbus_host_t *host);
  /* [any-thread] Non-zero on a worker running tiles or tasks. */
  int32_t (*is_render_thread)(const nimbus_host_t *host);
} nimbus_host_thread_check_v1_t;

#ifdef __cplusplus
}
#endif

#endif /* NIMBUS_HOST_H */
