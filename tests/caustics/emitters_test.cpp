// The solver's emission target (emitters.hpp): photon directions of finite lights aimed at the bounding
// sphere of the sharp surfaces. Checked: the cone sampler against its pdf (chi-square), that the cone
// just covers the target, that it stays exact for a small target far away (narrow cones), and that
// the camera side's lp equals the photon side's density for the directions photons are sent along, and
// that the sun's emission rectangle covers its box from every direction in the sun's cone.
#include <gtest/gtest.h>

#include <cmath>

#include "chi_square.hpp"
#include "emitters.hpp"

namespace nimbus::caustics {
namespace {

using test::ChiSquareConfig;
using test::Pcg32;

float uniform(Pcg32 &rng) { return rng.uniform(); }

// The host's emission densities for the lights of these tests (the lights service's pdf_emission, whose
// own agreement with sample_emission tests/lights checks), by light index: a point light, a spot of
// half angle 0.5 rad along (-1, 0, -1), a one-sided area light of area 1/4, and suns.
float pdf_dir_of(uint32_t light, const Vec3f &n, const Vec3f &w) {
  switch (light) {
    case 0:
      return kUniformSpherePdf;
    case 1:
      return dot(w, normalize(Vec3f(-1, 0, -1))) >= std::cos(0.5f) ? uniform_cone_pdf(std::cos(0.5f)) : 0.0f;
    default:
      return cosine_hemisphere_pdf(dot(n, w));
  }
}
const nimbus_host_lights_v1_t kStubLights = [] {
  nimbus_host_lights_v1_t t{};
  t.struct_size = sizeof(t);
  t.pdf_emission = [](const nimbus_host_t *, uint32_t light, const float *, const float n[3],
                      const float dir[3], float *pdf_pos, float *pdf_dir) {
    *pdf_pos = light == 2 ? 4.0f : 1.0f;
    *pdf_dir = pdf_dir_of(light, Vec3f::load(n), Vec3f::load(dir));
  };
  return t;
}();
// A sun's direction density: its uniform cone (cos of the half angle in cos_half, 1: a delta direction).
float g_sun_cos_half = 1;
const nimbus_host_lights_v1_t kStubSun = [] {
  nimbus_host_lights_v1_t t{};
  t.struct_size = sizeof(t);
  t.pdf_emission = [](const nimbus_host_t *, uint32_t, const float *, const float *, const float *,
                      float *pdf_pos, float *pdf_dir) {
    *pdf_pos = 123.0f;  // the host's disk: the solver uses its own
    *pdf_dir = g_sun_cos_half >= 1 ? 1.0f : uniform_cone_pdf(g_sun_cos_half);
  };
  return t;
}();

TEST(CausticsEmitters, ConeSamplerMatchesItsPdf) {
  // A tilted cone of ~34 degrees (a 0.5 sphere 0.9 away), against the pdf over the whole sphere.
  const Vec3f from(0.3f, -0.2f, 0.1f), center = from + normalize(Vec3f(0.4f, 0.7f, -0.6f)) * 0.9f;
  const EmissionCone cone = EmissionCone::towards(from, center, 0.5f);
  ASSERT_TRUE(cone.active());
  ChiSquareConfig cfg;
  cfg.seed = 7;
  const auto result = test::chi_square_test(
      [&](Pcg32 &rng) -> std::optional<Vec3f> {
        const float u0 = uniform(rng), u1 = uniform(rng);
        return cone.sample(u0, u1);
      },
      [&](const Vec3f &w) { return cone.contains(w) ? double(cone.pdf()) : 0.0; }, cfg);
  EXPECT_TRUE(result.error.empty()) << result.error;
  EXPECT_GT(result.p_value, 0.01) << result.describe();
  EXPECT_NEAR(result.pdf_integral, 1.0, 2e-3) << result.describe();
}

// Narrow cones are below the sphere grid's resolution: histogram them in the cone's own coordinates,
// (1 - cos theta) / (1 - cos theta_max) and phi, where the distribution is exactly uniform.
TEST(CausticsEmitters, NarrowConeSamplerIsUniform) {
  for (const float dist : {10.0f, 1e3f}) {
    const Vec3f from(0.3f, -0.2f, 0.1f), center = from + normalize(Vec3f(0.4f, 0.7f, -0.6f)) * dist;
    const EmissionCone cone = EmissionCone::towards(from, center, 0.5f);
    ASSERT_TRUE(cone.active());
    const Frame frame = Frame::from_normal(cone.axis);
    constexpr int kT = 20, kPhi = 20, kSamples = 400000;
    std::vector<int> counts(kT * kPhi, 0);
    Pcg32 rng(11);
    for (int i = 0; i < kSamples; ++i) {
      const Vec3f local = frame.to_local(cone.sample(uniform(rng), uniform(rng)));
      // 1 - cos from sin^2 (exact for narrow cones): 1 - cos = sin^2 / (1 + cos).
      const double sin2 = double(local.x) * local.x + double(local.y) * local.y;
      const double t = sin2 / (1 + double(local.z)) / double(cone.one_minus_cos);
      const double phi = std::atan2(double(local.y), double(local.x)) + M_PI;
      const int ti = std::min(kT - 1, int(t * kT)), pi = std::min(kPhi - 1, int(phi / (2 * M_PI) * kPhi));
      ASSERT_LT(t, 1.0 + 1e-3) << "outside the cone";
      ++counts[size_t(ti * kPhi + pi)];
    }
    const double expected = double(kSamples) / (kT * kPhi);
    double chi2 = 0;
    for (const int c : counts) chi2 += (c - expected) * (c - expected) / expected;
    const double p = test::chi_square_survival(chi2, kT * kPhi - 1);
    EXPECT_GT(p, 0.01) << "distance " << dist << ": chi2 " << chi2;
  }
}

TEST(CausticsEmitters, ConeJustCoversTheTarget) {
  Pcg32 rng(3);
  const Vec3f from(1, 2, 3), center(-1, 0.5f, 2);
  const float radius = 0.7f;
  const EmissionCone cone = EmissionCone::towards(from, center, radius);
  ASSERT_TRUE(cone.active());
  for (int i = 0; i < 10000; ++i) {
    // Every point of the target is inside the cone ...
    const Vec3f on = center + sample_uniform_sphere(uniform(rng), uniform(rng)) * (radius * 0.999f);
    EXPECT_TRUE(cone.contains(normalize(on - from)));
    // ... and every sampled direction passes within the target's radius of its centre.
    const Vec3f w = cone.sample(uniform(rng), uniform(rng));
    const Vec3f d = center - from;
    EXPECT_LE(length(d - w * dot(d, w)), radius * 1.0001f);
  }
  // Inside the target every direction may reach it: no cone.
  EXPECT_FALSE(EmissionCone::towards(center + Vec3f(0.1f, 0, 0), center, radius).active());
  EXPECT_FALSE(EmissionCone::towards(center, center, radius).active());
}

// A 1 cm target 1 km away: 1 - cos of the half angle is ~5e-11, far below float's resolution of cos
// near 1 (6e-8), yet the cone's pdf is right and its directions hit the target. (Much further, a float
// unit vector itself cannot aim at it: its angular resolution is ~6e-8 rad.)
TEST(CausticsEmitters, NarrowConeStaysExact) {
  Pcg32 rng(5);
  const Vec3f from(0, 0, 0), center(300, -400, 866);
  const float radius = 0.01f;
  const EmissionCone cone = EmissionCone::towards(from, center, radius);
  ASSERT_TRUE(cone.active());
  const double d2 = double(length_squared(center - from));
  const double expected_solid_angle = 2 * M_PI * (double(radius) * radius / d2) / 2;  // ~ pi (r/d)^2
  EXPECT_NEAR(1.0 / cone.pdf() / expected_solid_angle, 1.0, 1e-3);
  // Float directions resolve ~6e-8 rad against a half angle of 1e-5: samples within ~1 % of the rim
  // may round to either side of it (harmless: the target has a 5 % margin, see caustics.cpp).
  int inside = 0, hits = 0;
  for (int i = 0; i < 10000; ++i) {
    const Vec3f w = cone.sample(uniform(rng), uniform(rng));
    inside += cone.contains(w) ? 1 : 0;
    const Vec3f d = center - from;
    hits += length(d - w * dot(d, w)) <= radius * 1.01f ? 1 : 0;
  }
  EXPECT_GE(inside, 9900);
  EXPECT_GE(hits, 9900);
}

// The camera side evaluates lp from the light, the emission point and the direction; it must equal the
// density the photon tracer used: P_sel * P_dir(cone) for directions it sends photons along, and 0
// outside the cone (those paths belong to path tracing).
TEST(CausticsEmitters, CameraSideDensityEqualsPhotonSide) {
  std::vector<Emitter> lights(3);
  lights[0].kind = EmitterKind::Point, lights[0].power = 2, lights[0].position = Vec3f(-2, 0, 2);
  lights[0].flags = NIMBUS_LIGHT_DELTA_POSITION;
  lights[1].kind = EmitterKind::Spot, lights[1].power = 1, lights[1].position = Vec3f(2, 0, 2);
  lights[1].flags = NIMBUS_LIGHT_DELTA_POSITION;
  lights[1].axis = normalize(Vec3f(-1, 0, -1)), lights[1].cos_theta_e = std::cos(0.5f);
  lights[2].kind = EmitterKind::Area, lights[2].power = 1;
  lights[2].flags = NIMBUS_LIGHT_AREA;
  EmitterSet set;
  set.build(lights, Vec3f(0, 0, 0), 10, nullptr, &kStubLights);
  // Before the probe the target is the scene's sphere: lights inside it emit as the host does.
  EXPECT_FLOAT_EQ(set.lp(0, Vec3f(-2, 0, 2), Vec3f(), Vec3f(0, 0, 1), Vec3f()), 0.5f * kUniformSpherePdf);
  EXPECT_FALSE(set.cone(2, Vec3f(0, 0, 3)).active());

  const Vec3f target(0, 0, 0.5f);
  set.set_target(target, 0.5f);
  Pcg32 rng(9);
  for (uint32_t l = 0; l < 3; ++l) {
    const Vec3f z = l == 2 ? Vec3f(0.1f, 0.05f, 3) : set[l].position;
    const Vec3f n(0, 0, -1);
    const EmissionCone cone = set.cone(l, z);
    ASSERT_TRUE(cone.active()) << "light " << l;
    const float photon_lp = set.selection_pmf(l) * (l == 2 ? 4.0f : 1.0f) * cone.pdf();
    for (int i = 0; i < 1000; ++i) {
      const Vec3f w = cone.sample(uniform(rng), uniform(rng));
      EXPECT_FLOAT_EQ(set.lp(l, z, n, w, z + w), photon_lp) << "light " << l;
    }
    // Away from the target: no photon is sent that way.
    EXPECT_EQ(set.lp(l, z, n, normalize(Vec3f(0.3f, 1, 0.2f)), z), 0.0f) << "light " << l;
  }
  // The spot keeps its own (here wider) cone only where the target's is wider than it.
  set.set_target(Vec3f(0, 0, 0), 50);
  EXPECT_FALSE(set[1].cone.active());
  EXPECT_FLOAT_EQ(set.lp(1, set[1].position, Vec3f(), set[1].axis, Vec3f()),
                  set.selection_pmf(1) * uniform_cone_pdf(set[1].cos_theta_e));
}

// The sun's emission rectangle (a pool's water: a flat 4 x 2 m box under an oblique sun): smaller than
// the disk around the target's sphere; every box point is reachable from every direction in the sun's
// cone; the camera side's lp along a photon's line equals the photon side's density, and is 0 for a
// line that misses the rectangle.
TEST(CausticsEmitters, SunRectangleCoversTheBox) {
  for (const bool delta : {false, true}) {
    std::vector<Emitter> lights(1);
    Emitter &sun = lights[0];
    sun.kind = EmitterKind::Sun, sun.power = 1, sun.axis = normalize(Vec3f(-0.35f, 0.55f, -1.0f));
    sun.flags = NIMBUS_LIGHT_INFINITE | (delta ? NIMBUS_LIGHT_DELTA_DIRECTION : 0u);
    sun.cos_theta_e = delta ? 1.0f : std::cos(0.5f * 0.53f * kPi / 180);
    g_sun_cos_half = sun.cos_theta_e;
    EmitterSet set;
    set.build(lights, Vec3f(0, 0, 0), 20, nullptr, &kStubSun);
    const Vec3f lo(-2, -1, -0.08f), hi(2, 1, 0.08f), center(0.1f, 0, 0);
    const float radius = 1.05f * length(hi - center);
    set.set_target(center, radius);  // no box: the disk
    EXPECT_FALSE(set[0].use_rect);
    EXPECT_FLOAT_EQ(set[0].pdf_pos, 1 / (kPi * radius * radius));
    set.set_target(center, radius, lo, hi);
    ASSERT_TRUE(set[0].use_rect);
    const float area = 1 / set[0].pdf_pos;
    const float projected = 8 * std::abs(sun.axis.z);  // the box's top face seen along the axis
    EXPECT_LT(area, 0.55f * kPi * radius * radius) << "delta " << delta;
    EXPECT_GT(area, projected);
    EXPECT_LT(area, 1.25f * projected) << "delta " << delta;

    Pcg32 rng(17 + delta);
    const float pdf_dir = delta ? 1.0f : uniform_cone_pdf(sun.cos_theta_e);
    for (int i = 0; i < 20000; ++i) {
      const Vec3f w = delta ? sun.axis
                            : Frame::from_normal(sun.axis).to_world(
                                  sample_uniform_cone(uniform(rng), uniform(rng), sun.cos_theta_e));
      const Vec3f x(lo.x + uniform(rng) * (hi.x - lo.x), lo.y + uniform(rng) * (hi.y - lo.y),
                    lo.z + uniform(rng) * (hi.z - lo.z));
      ASSERT_TRUE(set.on_target(0, x, w)) << "box point not covered, delta " << delta;
      const Vec3f o = set.emission_origin(0, w, uniform(rng), uniform(rng));
      const Vec3f p = o + w * (20 + 5 * uniform(rng));
      EXPECT_FLOAT_EQ(set.lp(0, Vec3f(), Vec3f(), w, p), set.selection_pmf(0) * set[0].pdf_pos * pdf_dir);
    }
    // A line well outside the rectangle: no photon travels along it.
    EXPECT_EQ(set.lp(0, Vec3f(), Vec3f(), sun.axis, Vec3f(0, 6, 0)), 0.0f);
  }
}

}  // namespace
}  // namespace nimbus::caustics
