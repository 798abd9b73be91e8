// nimbus.host.lights@1.
#include <cstring>

#include "abi/host_services.hpp"
#include "abi/service_tables.hpp"

namespace nimbus {
namespace {

uint32_t count(const nimbus_host_t *host) { return world_of(host).lights.count(); }

// The info struct as SDK 1.0 and 1.1 made it, and as far as `area` (since 1.2): a caller's struct_size
// says which members it has, and the host writes those only.
constexpr size_t kInfoSize10 = offsetof(nimbus_light_info_t, area);
constexpr size_t kInfoSize12 = offsetof(nimbus_light_info_t, area) + sizeof(float);

nimbus_status_t info(const nimbus_host_t *host, uint32_t light, nimbus_light_info_t *out) {
  const World &world = world_of(host);
  if (!out || light >= world.lights.count() || out->header.struct_size < kInfoSize10)
    return NIMBUS_E_INVALID_ARG;
  const uint32_t size = out->header.struct_size;
  const void *next = out->header.next;
  nimbus_light_info_t full{};
  light_fill_info(world.lights[light], world.lights.scene(), full);
  const size_t covered = size >= kInfoSize12 ? kInfoSize12 : kInfoSize10;
  std::memcpy(reinterpret_cast<char *>(out) + sizeof(nimbus_struct_header_t),
              reinterpret_cast<const char *>(&full) + sizeof(nimbus_struct_header_t),
              covered - sizeof(nimbus_struct_header_t));
  out->header = {size, NIMBUS_S_TYPE_LIGHT_INFO, next};
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

void sample_incident_at(const nimbus_host_t *host, uint32_t light, const nimbus_interaction_t *ix,
                        const float u[2], float time, nimbus_light_incident_t *out) {
  const World &world = world_of(host);
  if (light >= world.lights.count()) {
    std::memset(out, 0, sizeof(*out));
    return;
  }
  Light moved;
  light_sample_incident(light_at(world.lights[light], time, moved), world.lights.scene(), *ix, u, *out);
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

void sample_emission_at(const nimbus_host_t *host, uint32_t light, const float u[4], float time,
                        nimbus_light_emission_t *out) {
  const World &world = world_of(host);
  if (light >= world.lights.count()) {
    std::memset(out, 0, sizeof(*out));
    return;
  }
  Light moved;
  light_sample_emission(light_at(world.lights[light], time, moved), world.lights.scene(), u, *out);
}

// p is not read: every emitter is uniform over its surface.
void eval_emission(const nimbus_host_t *host, uint32_t light, const float *, const float n[3],
                   const float dir[3], float Le[3]) {
  const World &ctx = world_of(host);
  if (light >= ctx.lights.count()) {
    Rgb(0).store(Le);
    return;
  }
  const Vec3f normal = n ? Vec3f::load(n) : Vec3f(0.0f);
  light_eval_emission(ctx.lights[light], n ? &normal : nullptr, Vec3f::load(dir)).store(Le);
}

void pdf_emission(const nimbus_host_t *host, uint32_t light, const float *, const float n[3],
                  const float dir[3], float *pdf_pos, float *pdf_dir) {
  const World &ctx = world_of(host);
  if (light >= ctx.lights.count()) {
    *pdf_pos = *pdf_dir = 0;
    return;
  }
  const Vec3f normal = n ? Vec3f::load(n) : Vec3f(0.0f);
  light_pdf_emission(ctx.lights[light], ctx.lights.scene(), n ? &normal : nullptr, Vec3f::load(dir), *pdf_pos,
                     *pdf_dir);
}

void eval_emission_at(const nimbus_host_t *host, uint32_t light, const float *, const float n[3],
                      const float dir[3], float time, float Le[3]) {
  const World &ctx = world_of(host);
  if (light >= ctx.lights.count()) {
    Rgb(0).store(Le);
    return;
  }
  const Vec3f normal = n ? Vec3f::load(n) : Vec3f(0.0f);
  Light moved;
  light_eval_emission(light_at(ctx.lights[light], time, moved), n ? &normal : nullptr, Vec3f::load(dir))
      .store(Le);
}

void pdf_emission_at(const nimbus_host_t *host, uint32_t light, const float *, const float n[3],
                     const float dir[3], float time, float *pdf_pos, float *pdf_dir) {
  const World &ctx = world_of(host);
  if (light >= ctx.lights.count()) {
    *pdf_pos = *pdf_dir = 0;
    return;
  }
  const Vec3f normal = n ? Vec3f::load(n) : Vec3f(0.0f);
  Light moved;
  light_pdf_emission(light_at(ctx.lights[light], time, moved), ctx.lights.scene(), n ? &normal : nullptr,
                     Vec3f::load(dir), *pdf_pos, *pdf_dir);
}

}  // namespace

const nimbus_host_lights_v1_t kLightsV1 = {sizeof(nimbus_host_lights_v1_t),
                                           count,
                                           info,
                                           sample_incident,
                                           pdf_incident,
                                           eval_emitted,
                                           eval_infinite,
                                           sample_emission,
                                           eval_emission,
                                           pdf_emission,
                                           sample_incident_at,
                                           sample_emission_at,
                                           eval_emission_at,
                                           pdf_emission_at};

}  // namespace nimbus
