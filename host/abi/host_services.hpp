// The host side of the C ABI: the nimbus_host_t that plugins receive and the service tables it hands out,
// each a thin forwarder to the C++ render context. Nothing C++ crosses: tables are plain C structs with
// static storage, and every entry catches nothing because nothing below throws on the hot path.
#pragma once

#include <nimbus/nimbus.h>

#include "render/render_context.hpp"

namespace nimbus {

class HostServices {
 public:
  // `ctx` may be null for discovery-only hosts (e.g. `nimbus plugins`): the service ids still resolve,
  // so required-service checks work, but no service may be called.
  explicit HostServices(RenderContext *ctx);
  HostServices(const HostServices &) = delete;
  HostServices &operator=(const HostServices &) = delete;

  const nimbus_host_t *host() const { return &host_; }
  RenderContext *context() const { return ctx_; }

  // The service table for "id" at revision rev, or null. Exposed for the plugin registry's checks.
  static const void *find_service(const char *id, uint32_t rev);

 private:
  nimbus_host_t host_{};
  RenderContext *ctx_;
};

// The render context behind a host handle (host_data).
inline RenderContext &context_of(const nimbus_host_t *host) {
  return *static_cast<HostServices *>(host->host_data)->context();
}

}  // namespace nimbus
