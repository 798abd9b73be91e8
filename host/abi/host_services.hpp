// The host side of the C ABI: the nimbus_host_t that plugins receive and the service tables it hands out,
// each a thin forwarder to the C++ world (what the render reads) and run state (what it writes). Nothing
// C++ crosses: tables are plain C structs with static storage, and every entry catches nothing because
// nothing below throws on the hot path.
#pragma once

#include <nimbus/nimbus.h>

#include "abi/run_state.hpp"
#include "world/world.hpp"

namespace nimbus {

class HostServices {
 public:
  // Both may be null for discovery-only hosts (e.g. `nimbus plugins`): the service ids still resolve, so
  // required-service checks work, but no service may be called. Both must outlive the services.
  explicit HostServices(const World *world, RunState *run = nullptr) : world_(world), run_(run) { init(); }
  HostServices(const HostServices &) = delete;
  HostServices &operator=(const HostServices &) = delete;

  const nimbus_host_t *host() const { return &host_; }
  const World *world() const { return world_; }
  RunState *run() const { return run_; }

  // The service table for "id" at revision rev, or null. Exposed for the plugin registry's checks.
  static const void *find_service(const char *id, uint32_t rev);

 private:
  void init();

  nimbus_host_t host_{};
  const World *world_;
  RunState *run_;
};

// The world and the run state behind a host handle (host_data).
inline const World &world_of(const nimbus_host_t *host) {
  return *static_cast<const HostServices *>(host->host_data)->world();
}
inline RunState &run_of(const nimbus_host_t *host) {
  return *static_cast<const HostServices *>(host->host_data)->run();
}

}  // namespace nimbus
