// nimbus.host.film@1.
#include "abi/host_services.hpp"
#include "abi/service_tables.hpp"

namespace nimbus {
namespace {

nimbus_element_t register_element(const nimbus_host_t *host, const char *name, uint32_t channels, uint32_t flags) {
  if (!name) return NIMBUS_ELEMENT_INVALID;
  return context_of(host).film->register_element(name, channels, flags);
}

int32_t is_active(const nimbus_host_t *host, nimbus_element_t el) {
  return context_of(host).film->is_active(el) ? 1 : 0;
}

void accumulate(const nimbus_host_t *host, const nimbus_thread_ctx_t *, nimbus_element_t el, uint32_t x,
                uint32_t y, const float *value) {
  context_of(host).film->accumulate(el, x, y, value);
}

void splat(const nimbus_host_t *host, const nimbus_thread_ctx_t *ctx, nimbus_element_t el, float fx, float fy,
           const float *value) {
  context_of(host).film->splat(ctx->worker_index, el, fx, fy, value);
}

}  // namespace

const nimbus_host_film_v1_t kFilmV1 = {sizeof(nimbus_host_film_v1_t), register_element, is_active, accumulate,
                                       splat};

}  // namespace nimbus
