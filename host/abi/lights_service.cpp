// nimbus.host.lights@1.
#include <cstring>

#include "abi/host_services.hpp"
#include "abi/service_tables.hpp"

namespace nimbus {
namespace {

uint32_t count(const nimbus_host_t *host) { return world_of(host).lights.count(); }

nimbus_status_t info(const nimbus_host_t *host, uint32_t light, nimbus_light_info_t *out) {
  const World &world = world_of(host);
  if (!out || light >= world.lights.count() || out->header.struct_size < sizeof(nimbus_light_info_t))
    return NIMBUS_E_INVALID_ARG;
  const uint32_t size = out->header.struct_size;
  const void *next = out->header.next;
  std::memset(reinterpret_cast<char *>(out) + sizeof(nimbus_struct_header_t), 0,
              sizeof(nimbus_light_info_t) - sizeof(nimbus_struct_header_t));
  out->header = {size, NIMBUS_S_TYPE_LIGHT_INFO, next};
  light_fill_info(world.lights[light], world.lights.scene(), *out);
  return NIMBUS_OK;
}

void sample_incident(const nimbus_host_t *host, uint32_t light, const nimbus_interaction_t *ix,
                     const float u[2], nimbus_light_incident_t *out) {
  const World &world = world_of(host);
  if (light >= world.lights.count()) {
    std::memset(out, 0, sizeof(*out));
    return;
  }
  light_sample_incident(world.lights[light], world.lights.scene(), *ix, u, *out);
}

float pdf_incident(const nimbus_host_t *host, uint32_t light, const nimbus_interaction_t *ref,
                   const float wi[3], const nimbus_interaction_t *on_light) {
  const World &world = world_of(host);
  if (light >= world.lights.count()) return 0;
  return light_pdf_incident(world.lights[light], world.lights.scene(), *ref, Vec3f::load(wi), on_light);
}

void eval_emitted(const nimbus_host_t *host, const nimbus_interaction_t *on_light, const float wo[3],
                  float L[3]) {
  const World &world = world_of(host);
  if (on_light->light_id >= world.lights.count()) {
    Rgb(0).store(L);
    return;
  }
  light_eval_emitted(world.lights[on_light->light_id], *on_light, Vec3f::load(wo)).store(L);
}

void eval_infinite(const nimbus_host_t *host, uint32_t light, const float dir[3], float L[3]) {
  const World &world = world_of(host);
  (light < world.lights.count() ? light_eval_infinite(world.lights[light], Vec3f::load(dir)) : Rgb(0))
      .store(L);
}

void sample_emission(const nimbus_host_t *host, uint32_t light, const float u[4],
                     nimbus_light_emission_t *out) {
  const World &world = world_of(host);
  if (light >= world.lights.count()) {
    std::memset(out, 0, sizeof(*out));
    return;
  }
  light_sample_emission(world.lights[light], world.lights.scene(), u, *out);
}

}  // namespace

const nimbus_host_lights_v1_t kLightsV1 = {sizeof(nimbus_host_lights_v1_t),
                                           count,
                                           info,
                                           sample_incident,
                                           pdf_incident,
                                           eval_emitted,
                                           eval_infinite,
                                           sample_emission};

}  // namespace nimbus
