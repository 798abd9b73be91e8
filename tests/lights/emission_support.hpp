// The lights service (nimbus.host.lights@1) of a scene given as YAML, as plugins see it: a render context
// behind the host handle, and thin helpers over the table's emission functions. Shared by the emission
// tests of tests/lights.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <nimbus/cpp/math.hpp>
#include "abi/host_services.hpp"
#include "scene/scene_parser.hpp"
#include "world/world.hpp"

#include "environment_map_fixture.hpp"

namespace nimbus::testing {

class LightsHarness {
 public:
  explicit LightsHarness(const std::string &yaml) {
    auto desc = parse_scene_string(yaml, "emission.yaml");
    EXPECT_TRUE(desc.ok()) << (desc.ok() ? "" : desc.error().message);
    desc_ = std::move(desc.value());
    auto ctx = World::build(desc_, desc_.render.filter);
    EXPECT_TRUE(ctx.ok()) << (ctx.ok() ? "" : ctx.error().message);
    ctx_ = std::move(ctx.value());
    services_ = std::make_unique<HostServices>(ctx_.get());
    lights_ = static_cast<const nimbus_host_lights_v1_t *>(
        services_->host()->get_service(services_->host(), NIMBUS_SERVICE_LIGHTS, 1));
    EXPECT_TRUE(NIMBUS_HAS_MEMBER(lights_, nimbus_host_lights_v1_t, pdf_emission));
  }

  const nimbus_host_t *host() const { return services_->host(); }
  const nimbus_host_lights_v1_t &table() const { return *lights_; }
  const World &context() const { return *ctx_; }
  uint32_t count() const { return lights_->count(host()); }

  nimbus_light_emission_t sample(uint32_t light, const float u[4]) const {
    nimbus_light_emission_t es;
    lights_->sample_emission(host(), light, u, &es);
    return es;
  }
  // pdf_emission at the photon's own origin, normal and direction.
  void pdf(uint32_t light, const nimbus_light_emission_t &es, float &pdf_pos, float &pdf_dir) const {
    lights_->pdf_emission(host(), light, es.org, es.n, es.dir, &pdf_pos, &pdf_dir);
  }
  // pdf_dir at a point p with normal n (area lights; ignored by others) along the unit direction dir.
  float pdf_dir(uint32_t light, const Vec3f &p, const Vec3f &n, const Vec3f &dir) const {
    float pa[3], na[3], da[3], pos = 0, pd = 0;
    p.store(pa), n.store(na), dir.store(da);
    lights_->pdf_emission(host(), light, pa, na, da, &pos, &pd);
    return pd;
  }
  float pdf_pos(uint32_t light, const Vec3f &p, const Vec3f &n) const {
    float pa[3], na[3], da[3], pos = 0, pd = 0;
    p.store(pa), n.store(na), n.store(da);
    lights_->pdf_emission(host(), light, pa, na, da, &pos, &pd);
    return pos;
  }
  Rgb eval(uint32_t light, const nimbus_light_emission_t &es) const {
    float Le[3];
    lights_->eval_emission(host(), light, es.org, es.n, es.dir, Le);
    return Rgb::load(Le);
  }
  nimbus_light_info_t info(uint32_t light) const {
    nimbus_light_info_t info{};
    info.header.struct_size = sizeof(info);
    EXPECT_EQ(lights_->info(host(), light, &info), NIMBUS_OK);
    return info;
  }

 private:
  SceneDesc desc_;
  std::unique_ptr<World> ctx_;
  std::unique_ptr<HostServices> services_;
  const nimbus_host_lights_v1_t *lights_ = nullptr;
};

// Test scenes: every kind of emitter the host has. Area lights: a one-sided rectangle (2 triangles),
// a sphere, a two-sided disk and a one-sided box (12 triangles of three sizes), all tilted.
inline const char *const kAreaScene = R"(
materials: { lamp: { type: diffuse, albedo: [0, 0, 0] } }
objects:
  - { shape: rectangle, size: [1, 2], material: lamp, emission: { radiance: [2, 2, 2] },
      transform: { rotate: [150, 0, 0], translate: [0.5, 0, 2] } }
  - { shape: sphere, center: [-1.5, 0.5, 1.5], radius: 0.6, material: lamp, emission: { radiance: [1, 3, 1] } }
  - { shape: disk, radius: 0.7, material: lamp, emission: { radiance: [4, 4, 4] }, two_sided: true,
      transform: { rotate: [0, 120, 0], translate: [1.5, 1, 1] } }
  - { shape: box, size: [1, 2, 3], material: lamp, emission: { radiance: [0.5, 1, 2] },
      transform: { rotate: [30, 20, 10], translate: [0, -3, 1] } }
)";
// Point and spot (a 45 degree cone whose last 15 degrees fall off), and a sun of 20 degrees' diameter
// (unphysically wide, so that its cone spans many histogram cells).
inline const char *const kDeltaScene = R"(
materials: { white: { type: diffuse } }
objects:
  - { shape: sphere, center: [0, 0, 0], radius: 3, material: white }
lights:
  - { type: point, position: [0.2, -0.3, 0.5], intensity: [3, 2, 1] }
  - { type: spot, position: [-0.5, 0.4, 1], direction: [0.3, -0.2, -1], cone: 45, softness: 15,
      intensity: [5, 4, 3] }
  - { type: sun, direction: [0.3, 0.2, -1], irradiance: [5, 5, 5], angular_diameter: 20 }
  - { type: sun, direction: [-0.2, 0.4, -1], irradiance: [2, 3, 4] }
)";

}  // namespace nimbus::testing
