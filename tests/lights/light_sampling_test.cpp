// Every light's sample_incident agrees with its pdf_incident and with brute force: the irradiance at a
// receiver estimated by light sampling equals the one found by tracing uniformly distributed rays and
// evaluating the emission they hit (area lights, spheres seen from outside, disks, sun, environments).
#include <gtest/gtest.h>

#include <cstdio>

#include <filesystem>
#include <random>

#include <nimbus/cpp/sampling.hpp>
#include "environment_map_fixture.hpp"
#include "lights/light_set.hpp"
#include "scene/scene_parser.hpp"

namespace nimbus {
namespace light_sampling_test {

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
void check_light(const Built &b, uint32_t l, const Vec3f &p, int n = 1000000) {
  std::mt19937 rng(17 + l);
  std::uniform_real_distribution<float> U(0, 1);
  const nimbus_interaction_t ref = receiver_at(p);
  const Light &light = b.lights[l];
  double e_light = 0, e_brute = 0, e_light2 = 0, e_brute2 = 0;  // sums and sums of squares
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
        const double v = luminance(Rgb::load(s.L)) * wi.z / s.pdf;
        e_light += v, e_light2 += v * v;
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
    const double v = luminance(L) * kPi;  // cos / pdf = pi
    e_brute += v, e_brute2 += v * v;
  }
  e_light /= n, e_brute /= n;
  // Standard errors of the two independent means, from their samples.
  const double se_light = std::sqrt(std::max(0.0, e_light2 / n - e_light * e_light) / n);
  const double se_brute = std::sqrt(std::max(0.0, e_brute2 / n - e_brute * e_brute) / n);
  const double sigma = std::hypot(se_light, se_brute);
  EXPECT_LE(pdf_mismatches, checked / 1000)
      << "light " << l << ": pdf_incident disagrees with the sample's pdf";
  EXPECT_LE(radiance_mismatches, checked / 1000)
      << "light " << l << ": the sample's radiance disagrees with light_eval_infinite";
  EXPECT_GT(e_brute, 0) << "light " << l;
  // The two estimates agree within 4 standard errors of their difference, and the counts make that a
  // check worth having: 4 sigma within 3 % of the irradiance.
  std::printf("light %u: light sampling %.5g, brute force %.5g, sigma %.3g (%.2f %%)\n", l, e_light, e_brute,
              sigma, 100 * sigma / e_brute);
  EXPECT_NEAR(e_light, e_brute, 4 * sigma)
      << "light " << l << ": light sampling " << e_light << ", brute force " << e_brute;
  EXPECT_LT(4 * sigma, 0.03 * e_brute) << "light " << l << ": too few samples for a 3 % check";
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
  // A large sun disk (6 degrees) so that brute force finds it often enough; brute force still hits it
  // in 1 of 500 directions, hence 8M samples for a standard error of 0.6 %.
  check_light(*b, 0, {0, 0, 0}, 8000000);
  check_light(*b, 1, {0, 0, 0});
}

// A photographed-style map (nearest texel, no interpolation), rotated, with a hot spot 10^4 above the
// rest: samples, pdfs and radiances agree with what escaping rays find.
TEST(LightSampling, EnvironmentMapAgreesWithBruteForce) {
  const std::string path = testing::write_environment_map("nimbus_light_sampling_map.exr");
  ASSERT_FALSE(HasFailure()) << "could not write " << path;
  auto b = build("environment: { map: " + path + ", rotate: 30 }\n");
  ASSERT_EQ(b->lights.count(), 1u);
  // The hot spot holds most of the irradiance and brute force rarely finds it: 6M samples for 0.7 %.
  check_light(*b, 0, {0, 0, 0}, 6000000);
  std::filesystem::remove(path);
}

TEST(LightSampling, UniformEnvironmentIrradianceIsPiTimesRadiance) {
  auto b = build("environment: { color: [0.5, 0.5, 0.5] }\n");
  ASSERT_EQ(b->lights.count(), 1u);
  check_light(*b, 0, {0, 0, 0});
}

}  // namespace light_sampling_test
}  // namespace nimbus
