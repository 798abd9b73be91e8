// nimbus.host.rng@1, progress@1, tasks@1, memory@1 and thread-check@1: the small services.
#include <tbb/parallel_for.h>

#include "core/denormals.hpp"

#include <cstdlib>

#include "abi/host_services.hpp"
#include "abi/service_tables.hpp"
#include "core/hash.hpp"

namespace nimbus {
namespace {

void derive(const nimbus_host_t *host, uint64_t key, uint64_t iteration, uint64_t stream, nimbus_rng_t *out) {
  *out = derive_rng(run_of(host).seed, key, iteration, stream);
}

void report(const nimbus_host_t *host, uint64_t done, uint64_t total, const char *phase) {
  RunState &run = run_of(host);
  std::lock_guard lock(run.phase_mutex);
  run.phase = phase ? phase : "";
  run.phase_done = done;
  run.phase_total = total;
}

int32_t cancelled(const nimbus_host_t *host) {
  const RunState &run = run_of(host);
  return run.cancel && run.cancel->load(std::memory_order_relaxed) ? 1 : 0;
}

void stat_add(const nimbus_host_t *host, const char *counter, double value) {
  if (!counter) return;
  RunState &run = run_of(host);
  std::lock_guard lock(run.stats_mutex);
  run.stats[counter] += value;
}

// Worker index of the calling thread inside the render arena (0 for the main thread outside it).
uint32_t worker_index() {
  const int i = tbb::this_task_arena::current_thread_index();
  return i < 0 ? 0u : uint32_t(i);
}

nimbus_status_t parallel_for(const nimbus_host_t *host, uint64_t count, uint64_t grain, nimbus_task_fn fn,
                             void *user) {
  if (!fn) return NIMBUS_E_INVALID_ARG;
  RunState &run = run_of(host);
  if (grain == 0) grain = 1;
  const uint64_t chunks = (count + grain - 1) / grain;
  // Fixed chunks (not TBB's adaptive ranges) so boundaries never depend on the thread count.
  run.arena->execute([&] {
    tbb::parallel_for(uint64_t(0), chunks, [&](uint64_t c) {
      const FlushDenormals float_mode;
      nimbus_thread_ctx_t tc{sizeof(nimbus_thread_ctx_t), worker_index(), run.worker_count, 0, nullptr, 0};
      const uint64_t begin = c * grain, end = std::min(count, begin + grain);
      fn(&tc, begin, end, user);
    });
  });
  return NIMBUS_OK;
}

uint32_t tasks_worker_count(const nimbus_host_t *host) { return run_of(host).worker_count; }

void *mem_alloc(const nimbus_host_t *, size_t bytes, size_t alignment) {
  if (alignment == 0 || (alignment & (alignment - 1)) != 0 || alignment > 4096) return nullptr;
  alignment = std::max(alignment, sizeof(void *));
  // aligned_alloc wants a size that is a multiple of the alignment; free() releases it whatever it was.
  const size_t size = (std::max<size_t>(bytes, 1) + alignment - 1) / alignment * alignment;
  return std::aligned_alloc(alignment, size);
}

void mem_free(const nimbus_host_t *, void *block) { std::free(block); }

int32_t is_main_thread(const nimbus_host_t *host) {
  return std::this_thread::get_id() == run_of(host).main_thread ? 1 : 0;
}

int32_t is_render_thread(const nimbus_host_t *) {
  return tbb::this_task_arena::current_thread_index() >= 0 ? 1 : 0;
}

}  // namespace

const nimbus_host_rng_v1_t kRngV1 = {sizeof(nimbus_host_rng_v1_t), derive};
const nimbus_host_progress_v1_t kProgressV1 = {sizeof(nimbus_host_progress_v1_t), report, cancelled,
                                               stat_add};
const nimbus_host_tasks_v1_t kTasksV1 = {sizeof(nimbus_host_tasks_v1_t), 0, parallel_for, tasks_worker_count};
const nimbus_host_memory_v1_t kMemoryV1 = {sizeof(nimbus_host_memory_v1_t), mem_alloc, mem_free};
const nimbus_host_thread_check_v1_t kThreadCheckV1 = {sizeof(nimbus_host_thread_check_v1_t), is_main_thread,
                                                      is_render_thread};

}  // namespace nimbus
