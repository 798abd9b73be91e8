#include "abi/host_services.hpp"

#include <cstdio>
#include <cstring>
#include <string_view>

#include "abi/service_tables.hpp"

namespace nimbus {
namespace {

// A lookup the host cannot answer is remembered, so that the plugin's failure that usually follows can
// name the service and revision it wanted.
const void *get_service(const nimbus_host_t *host, const char *id, uint32_t rev) {
  const void *table = HostServices::find_service(id, rev);
  RunState *run = host ? static_cast<HostServices *>(host->host_data)->run() : nullptr;
  if (!table && run) {
    std::lock_guard lock(run->missing_services_mutex);
    run->missing_services.push_back(std::string(id ? id : "(null)") + "@" + std::to_string(rev));
  }
  return table;
}

void log_message(const nimbus_host_t *host, nimbus_log_level_t level, const char *plugin_id,
                 const char *msg) {
  RunState *run = static_cast<HostServices *>(host->host_data)->run();
  const std::string id = plugin_id ? plugin_id : "";
  const std::string text = msg ? msg : "";
  if (run && run->log) {
    run->log(level, id, text);
  } else if (level >= NIMBUS_LOG_WARNING) {
    std::fprintf(stderr, "nimbus: %s%s%s\n", id.c_str(), id.empty() ? "" : ": ", text.c_str());
  }
}

}  // namespace

void HostServices::init() {
  host_.struct_size = sizeof(nimbus_host_t);
  host_.abi = NIMBUS_ABI_VERSION_INIT;
  host_.host_data = this;
  host_.get_service = get_service;
  host_.log = log_message;
}

const void *HostServices::find_service(const char *id, uint32_t rev) {
  if (!id || rev != 1) return nullptr;  // every service is at revision 1
  const std::string_view s(id);
  if (s == NIMBUS_SERVICE_SCENE_QUERY) return &kSceneQueryV1;
  if (s == NIMBUS_SERVICE_CAMERA) return &kCameraV1;
  if (s == NIMBUS_SERVICE_BSDF) return &kBsdfV1;
  if (s == NIMBUS_SERVICE_LIGHTS) return &kLightsV1;
  if (s == NIMBUS_SERVICE_FILM) return &kFilmV1;
  if (s == NIMBUS_EXT_LIGHTMIX) return &kLightMixV1;
  if (s == NIMBUS_SERVICE_RNG) return &kRngV1;
  if (s == NIMBUS_SERVICE_PROGRESS) return &kProgressV1;
  if (s == NIMBUS_SERVICE_TASKS) return &kTasksV1;
  if (s == NIMBUS_SERVICE_MEMORY) return &kMemoryV1;
  if (s == NIMBUS_SERVICE_THREAD_CHECK) return &kThreadCheckV1;
  if (s == NIMBUS_SERVICE_SPECTRAL) return &kSpectralV1;  // since 1.7
  return nullptr;
}

}  // namespace nimbus
