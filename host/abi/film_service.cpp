// nimbus.host.film@1 and nimbus.ext.lightmix@1.
#include "abi/host_services.hpp"
#include "abi/service_tables.hpp"

namespace nimbus {
namespace {

nimbus_element_t register_element(const nimbus_host_t *host, const char *name, uint32_t channels,
                                  uint32_t flags) {
  if (!name) return NIMBUS_ELEMENT_INVALID;
  return run_of(host).film.register_element(name, channels, flags);
}

int32_t is_active(const nimbus_host_t *host, nimbus_element_t el) {
  return run_of(host).film.is_active(el) ? 1 : 0;
}

// Odd iterations' beauty also feeds the error estimate's half film (only with --target-error).
Film *half_film(const RunState &run, nimbus_element_t el) {
  return el == NIMBUS_ELEMENT_BEAUTY && run.error_estimate && ErrorEstimate::is_odd(run.task_iteration)
             ? &run.error_estimate->half()
             : nullptr;
}

// A write outside the worker's tile is dropped and counted: it would race with the tile's owner.
bool outside_tile(RunState &run, const nimbus_thread_ctx_t *tc, uint32_t x, uint32_t y) {
  if (run.in_tile(tc, x, y)) return false;
  run.outside_tile_writes.fetch_add(1, std::memory_order_relaxed);
  return true;
}

void accumulate(const nimbus_host_t *host, const nimbus_thread_ctx_t *tc, nimbus_element_t el, uint32_t x,
                uint32_t y, const float *value) {
  RunState &run = run_of(host);
  if (outside_tile(run, tc, x, y)) return;
  run.film.accumulate(el, x, y, value);
  if (Film *half = half_film(run, el)) half->accumulate(el, x, y, value);
}

void splat(const nimbus_host_t *host, const nimbus_thread_ctx_t *tc, nimbus_element_t el, float fx, float fy,
           const float *value) {
  RunState &run = run_of(host);
  run.film.splat(tc->worker_index, el, fx, fy, value);
  if (Film *half = half_film(run, el)) half->splat(tc->worker_index, el, fx, fy, value);
}

int32_t lightmix_is_active(const nimbus_host_t *host) {
  return run_of(host).lightmix_elements.empty() ? 0 : 1;
}

uint32_t lightmix_group_count(const nimbus_host_t *host) {
  return uint32_t(world_of(host).lights.group_names().size());
}

void lightmix_accumulate(const nimbus_host_t *host, const nimbus_thread_ctx_t *tc, uint32_t group, uint32_t x,
                         uint32_t y, const float value[3]) {
  RunState &run = run_of(host);
  if (outside_tile(run, tc, x, y)) return;
  if (group < run.lightmix_elements.size()) run.film.accumulate(run.lightmix_elements[group], x, y, value);
}

void lightmix_splat(const nimbus_host_t *host, const nimbus_thread_ctx_t *tc, uint32_t group, float fx,
                    float fy, const float value[3]) {
  RunState &run = run_of(host);
  if (group < run.lightmix_elements.size())
    run.film.splat(tc->worker_index, run.lightmix_elements[group], fx, fy, value);
}

}  // namespace

const nimbus_ext_lightmix_v1_t kLightMixV1 = {sizeof(nimbus_ext_lightmix_v1_t), lightmix_is_active,
                                              lightmix_group_count, lightmix_accumulate, lightmix_splat};

const nimbus_host_film_v1_t kFilmV1 = {sizeof(nimbus_host_film_v1_t), register_element, is_active, accumulate,
                                       splat};

}  // namespace nimbus
