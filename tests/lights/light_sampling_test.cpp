// Every light's sample_incident agrees with its pdf_incident and with brute force: the irradiance at a
// receiver estimated by light sampling equals the one found by tracing uniformly distributed rays and
// evaluating the emission they hit (area lights, spheres seen from outside, disks, sun, environments).
#include <gtest/gtest.h>

#include <filesystem>
#include <random>

#include <nimbus/cpp/sampling.hpp>
#include "environment_map_fixture.hpp"
#include "lights/light_set.hpp"
#include "scene/scene_parser.hpp"

namespace nimbus {
namespace {

struct Built {
  SceneDesc desc;
  std::unique_ptr<GeometryScene> geo;
  LightSet lights;
};

std::unique_ptr<Built> build(const std::string &yaml) {
  auto b = std::make_unique<Built>();
  auto d = parse_scene_string(yaml, "lights.yaml");
  EXPECT_TRUE(d.ok()) << (d.ok() ? "" : d.error().message);
  b->desc = std::move(d.value());
  auto g = GeometryScene::build(b->desc);
  EXPECT_TRUE(g.ok());
  b->geo = std::move(g.value());
  auto l = LightSet::build(b->desc, *b->geo);
  EXPECT_TRUE(l.ok()) << (l.ok() ? "" : l.error().message);
  b->lights = std::move(l.value());
  return b;
}

nimbus_interaction_t receiver_at(const Vec3f &p) {
  nimbus_interaction_t ix{};
  p.store(ix.p);
  Vec3f(0, 0, 1).store(ix.ng);
  Vec3f(0, 0, 1).store(ix.ns);
  ix.eps = 1e-5f;
  return ix;
}

// Irradiance at the receiver (upper hemisphere) from light `l` by light sampling, and by brute force.
void check_light(const Built &b, uint32_t l, const Vec3f &p, int n = 200000) {
  std::mt19937 rng(17 + l);
  std::uniform_real_distribution<float> U(0, 1);
  const nimbus_interaction_t ref = receiver_at(p);
  const Light &light = b.lights[l];
  double e_light = 0, e_brute = 0;
  int checked = 0, pdf_mismatches = 0, radiance_mismatches = 0;
  for (int i = 0; i < n; ++i) {
    const float u[2] = {U(rng), U(rng)};
    nimbus_light_incident_t s;
    light_sample_incident(light, b.lights.scene(), ref, u, s);
    if (s.pdf > 0 && s.wi[2] > 0) {
      const Vec3f wi = Vec3f::load(s.wi);
      // Visibility: only the light itself may be hit.
      nimbus_ray_t ray{};
      p.store(ray.org);
      wi.store(ray.dir);
      ray.tfar = kInfinity;
      nimbus_hit_t hit;
      b.geo->intersect(ray, hit);
      const bool infinite = s.flags & NIMBUS_LIGHT_INFINITE;
      if (infinite ? hit.geom_id == NIMBUS_NONE
                   : hit.geom_id != NIMBUS_NONE && b.geo->shapes()[hit.geom_id].light_id == l) {
        e_light += luminance(Rgb::load(s.L)) * wi.z / s.pdf;
        // pdf_incident must reproduce the sample's pdf.
        nimbus_interaction_t on{};
        if (!infinite) b.geo->interaction(ray, hit, on);
        const float pdf = light_pdf_incident(light, b.lights.scene(), ref, wi, infinite ? nullptr : &on);
        // Directions within rounding of a texel edge of an environment map may map back to the
        // neighbouring texel: count such disagreements instead of failing on each.
        ++checked;
        if (std::abs(pdf / s.pdf - 1.0f) > 2e-3f) ++pdf_mismatches;
        // The sample's radiance is what a ray escaping along wi finds (environments take it from the
        // sampled texel: the same texel-edge allowance).
        if (infinite && std::abs(luminance(Rgb::load(s.L)) - luminance(light_eval_infinite(light, wi))) >
                            1e-3f * luminance(Rgb::load(s.L)))
          ++radiance_mismatches;
      }
    }
    // Brute force: cosine-weighted directions, radiance from whatever they hit.
    const Vec3f w = sample_cosine_hemisphere(U(rng), U(rng));
    nimbus_ray_t ray{};
    p.store(ray.org);
    w.store(ray.dir);
    ray.tfar = kInfinity;
    nimbus_hit_t hit;
    b.geo->intersect(ray, hit);
    Rgb L(0);
    if (hit.geom_id == NIMBUS_NONE) {
      L = light_eval_infinite(light, w);
    } else if (b.geo->shapes()[hit.geom_id].light_id == l) {
      nimbus_interaction_t on;
      b.geo->interaction(ray, hit, on);
      L = light_eval_emitted(light, on, -w);
    }
    e_brute += luminance(L) * kPi;  // cos / pdf = pi
  }
  e_light /= n, e_brute /= n;
  EXPECT_LE(pdf_mismatches, checked / 1000)
      << "light " << l << ": pdf_incident disagrees with the sample's pdf";
  EXPECT_LE(radiance_mismatches, checked / 1000)
      << "light " << l << ": the sample's radiance disagrees with light_eval_infinite";
  EXPECT_GT(e_brute, 0) << "light " << l;
  EXPECT_NEAR(e_light / e_brute, 1.0, 0.03)
      << "light " << l << ": light sampling " << e_light << ", brute force " << e_brute;
}

TEST(LightSampling, AreaLightsAgreeWithBruteForce) {
  auto b = build(R"(
materials: { lamp: { type: diffuse, albedo: [0, 0, 0] } }
objects:
  - { shape: rectangle, size: [1, 2], material: lamp, emission: { radiance: [2, 2, 2] },
      transform: { rotate: [150, 0, 0], translate: [0.5, 0, 2] } }
  - { shape: sphere, center: [-1.5, 0.5, 1.5], radius: 0.6, material: lamp, emission: { radiance: [1, 3, 1] } }
  - { shape: disk, radius: 0.7, material: lamp, emission: { radiance: [4, 4, 4] }, two_sided: true,
      transform: { rotate: [0, 120, 0], translate: [1.5, 1, 1] } }
)");
  ASSERT_EQ(b->lights.count(), 3u);
  for (uint32_t l = 0; l < 3; ++l) check_light(*b, l, {0, 0, 0});
}

TEST(LightSampling, SunDiskAndEnvironmentAgreeWithBruteForce) {
  auto b = build(R"(
lights:
  - { type: sun, direction: [0.3, 0.2, -1], irradiance: [5, 5, 5], angular_diameter: 6 }
environment: { type: sky, turbidity: 3 }
)");
  ASSERT_EQ(b->lights.count(), 2u);
  // A large sun disk (6 degrees) so that brute force finds it often enough.
  check_light(*b, 0, {0, 0, 0}, 400000);
  check_light(*b, 1, {0, 0, 0});
}

// A photographed-style map (nearest texel, no interpolation), rotated, with a hot spot 10^4 above the
// rest: samples, pdfs and radiances agree with what escaping rays find.
TEST(LightSampling, EnvironmentMapAgreesWithBruteForce) {
  const std::string path = testing::write_environment_map("nimbus_light_sampling_map.exr");
  ASSERT_FALSE(HasFailure()) << "could not write " << path;
  auto b = build("environment: { map: " + path + ", rotate: 30 }\n");
  ASSERT_EQ(b->lights.count(), 1u);
  check_light(*b, 0, {0, 0, 0}, 400000);
  std::filesystem::remove(path);
}

TEST(LightSampling, UniformEnvironmentIrradianceIsPiTimesRadiance) {
  auto b = build("environment: { color: [0.5, 0.5, 0.5] }\n");
  ASSERT_EQ(b->lights.count(), 1u);
  check_light(*b, 0, {0, 0, 0});
}

}  // namespace
}  // namespace nimbus
