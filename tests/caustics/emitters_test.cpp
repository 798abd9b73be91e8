// The solver's projection maps (emitters.hpp, sharp_targets.hpp): photons of finite lights aimed at
// spheres around the sharp objects. Checked: the cone sampler against its pdf (chi-square), that the cone
// just covers the target, that it stays exact for a small target far away (narrow cones), the mixture of
// a light's own emission and its cones against the density the camera side evaluates, that the sun's
// emission rectangle covers its box from every direction in the sun's cone, and the clustering.
#include <gtest/gtest.h>

#include <cmath>

#include "chi_square.hpp"
#include "emitter_stubs.hpp"
#include "emitters.hpp"
#include "merging.hpp"

namespace nimbus::caustics {
namespace emitters_test {

using stubs::kStubLights;
using stubs::pdf_dir_of;
using stubs::three_lights;
using stubs::two_targets;
using test::ChiSquareConfig;
using test::Pcg32;

float uniform(Pcg32 &rng) { return rng.uniform(); }

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

// A direction of light l's own emission (the stub host's distributions of pdf_dir_of).
Vec3f own_direction(uint32_t l, const Emitter &e, const Vec3f &n, Pcg32 &rng) {
  const float u0 = uniform(rng), u1 = uniform(rng);
  if (l == 0) return sample_uniform_sphere(u0, u1);
  if (l == 1) return Frame::from_normal(e.axis).to_world(sample_uniform_cone(u0, u1, e.cos_theta_e));
  return Frame::from_normal(n).to_world(sample_cosine_hemisphere(u0, u1));
}

// Every finite light's projection map: the mixture sampler (own emission or a cone towards each target)
// against the mixture density the camera side evaluates, by chi-square over the sphere of directions;
// the spot drops the side target outside its cone; the own share is at least the defensive 10 %.
TEST(CausticsEmitters, ProjectionMapSamplerMatchesItsDensity) {
  EmitterSet set;
  set.build(three_lights(), Vec3f(0, 0, 0), 10, nullptr, &kStubLights, two_targets());
  ASSERT_EQ(set.targets().clusters.size(), 2u);
  EXPECT_EQ(set[0].aims.size(), 2u);
  EXPECT_EQ(set[1].aims.size(), 1u) << "the side target lies outside the spot's cone";
  EXPECT_EQ(set[2].aims.size(), 2u);
  const Vec3f n(0, 0, -1);
  for (uint32_t l = 0; l < 3; ++l) {
    const Emitter &e = set[l];
    float shares = e.own;
    for (const Aim &a : e.aims) shares += a.share;
    EXPECT_NEAR(shares, 1.0f, 1e-5f) << "light " << l;
    EXPECT_GE(e.own, kOwnShare - 1e-6f);
    const Vec3f z = e.position;
    ChiSquareConfig cfg;
    cfg.seed = 40 + l;
    const auto result = test::chi_square_test(
        [&](Pcg32 &rng) -> std::optional<Vec3f> {
          const Vec3f own = own_direction(l, e, n, rng);
          const float um = uniform(rng), u0 = uniform(rng), u1 = uniform(rng);
          return set.sample_direction(l, z, um, u0, u1, own);
        },
        [&](const Vec3f &w) { return double(set.pdf_dir(l, z, w, pdf_dir_of(l, n, w))); }, cfg);
    EXPECT_TRUE(result.error.empty()) << "light " << l << ": " << result.error;
    EXPECT_GT(result.p_value, 0.01) << "light " << l << ": " << result.describe();
    EXPECT_NEAR(result.pdf_integral, 1.0, 5e-3) << "light " << l << ": " << result.describe();
    // The camera side's lp is the selection, the host's position density and this mixture.
    const Vec3f w = normalize(Vec3f(0, 0, 0.5f) - z);
    EXPECT_FLOAT_EQ(set.lp(l, z, n, w, z + w), set.selection_pmf(l) * (l == 2 ? 4.0f : 1.0f) *
                                                   set.pdf_dir(l, z, w, pdf_dir_of(l, n, w)));
  }
}

// A small ball far from a point light: the light's own (uniform) emission would send ~1e-5 of its
// photons at it; the projection map sends 90 %, and the density there is the cone's.
TEST(CausticsEmitters, SmallFarTargetGetsMostPhotons) {
  std::vector<Target> objects = {
      {{Vec3f(30, 0, 0.05f), 0.05f}, Vec3f(29.95f, -0.05f, 0), Vec3f(30.05f, 0.05f, 0.1f)}};
  SharpTargets t;
  cluster(objects, kMaxTargets, t.clusters);
  t.all = enclose(t.clusters);
  std::vector<Emitter> lights = three_lights();
  lights.resize(1);
  EmitterSet set;
  set.build(lights, Vec3f(0, 0, 0), 50, nullptr, &kStubLights, t);
  ASSERT_EQ(set[0].aims.size(), 1u);
  EXPECT_NEAR(set[0].own, kOwnShare, 1e-6f);
  Pcg32 rng(5);
  int hits = 0;
  for (int i = 0; i < 10000; ++i) {
    const Vec3f w = set.sample_direction(0, set[0].position, uniform(rng), uniform(rng), uniform(rng),
                                         own_direction(0, set[0], Vec3f(), rng));
    const Vec3f d = Vec3f(30, 0, 0.05f) - set[0].position;
    hits += dot(d, w) > 0 && length(d - w * dot(d, w)) <= 0.05f ? 1 : 0;
  }
  EXPECT_NEAR(hits / 1e4, 1 - kOwnShare, 0.015);  // 5 sigma of a binomial of 1e4 at 0.9
}

// The sun's emission rectangle (a pool's water: a flat 4 x 2 m box under an oblique sun): smaller than
// the disk around the target's sphere; every box point is reachable from every direction in the sun's
// cone; the camera side's lp along a photon's line equals the photon side's density (the rectangle's
// share plus the scene disk's), and is the scene disk's alone for a line that misses the rectangle.
TEST(CausticsEmitters, SunRectangleCoversTheBox) {
  for (const bool delta : {false, true}) {
    std::vector<Emitter> lights(1);
    Emitter &sun = lights[0];
    sun.kind = EmitterKind::Sun, sun.power = 1, sun.axis = normalize(Vec3f(-0.35f, 0.55f, -1.0f));
    sun.flags = NIMBUS_LIGHT_INFINITE | (delta ? NIMBUS_LIGHT_DELTA_DIRECTION : 0u);
    sun.cos_theta_e = delta ? 1.0f : std::cos(0.5f * 0.53f * kPi / 180);
    g_sun_cos_half = sun.cos_theta_e;
    const Vec3f lo(-2, -1, -0.08f), hi(2, 1, 0.08f), center(0.1f, 0, 0);
    const float radius = 1.05f * length(hi - center);
    SharpTargets t;
    t.clusters = {{{center, radius}, lo, hi}};
    t.all = t.clusters[0];
    EmitterSet set;
    set.build(lights, Vec3f(0, 0, 0), 20, nullptr, &kStubSun, t);
    ASSERT_TRUE(set[0].use_rect);
    EXPECT_NEAR(set[0].own, kOwnShare, 1e-6f);
    const float area = 1 / set[0].pdf_pos;
    const float projected = 8 * std::abs(sun.axis.z);  // the box's top face seen along the axis
    EXPECT_LT(area, 0.55f * kPi * radius * radius) << "delta " << delta;
    EXPECT_GT(area, projected);
    EXPECT_LT(area, 1.25f * projected) << "delta " << delta;

    Pcg32 rng(17 + delta);
    const float pdf_dir = delta ? 1.0f : uniform_cone_pdf(sun.cos_theta_e);
    const float scene_disk = kOwnShare / (kPi * 20 * 20);
    for (int i = 0; i < 20000; ++i) {
      const Vec3f w = delta ? sun.axis
                            : Frame::from_normal(sun.axis).to_world(
                                  sample_uniform_cone(uniform(rng), uniform(rng), sun.cos_theta_e));
      const Vec3f x(lo.x + uniform(rng) * (hi.x - lo.x), lo.y + uniform(rng) * (hi.y - lo.y),
                    lo.z + uniform(rng) * (hi.z - lo.z));
      const float on = scene_disk + (1 - kOwnShare) * set[0].pdf_pos;
      ASSERT_FLOAT_EQ(set.sun_pdf_pos(0, x, w), on) << "box point not covered, delta " << delta;
      const float um = uniform(rng);
      const Vec3f o = set.emission_origin(0, w, um, uniform(rng), uniform(rng));
      const Vec3f p = o + w * (20 + 5 * uniform(rng));
      EXPECT_FLOAT_EQ(set.lp(0, Vec3f(), Vec3f(), w, p),
                      set.selection_pmf(0) * set.sun_pdf_pos(0, o, w) * pdf_dir);
      if (um >= kOwnShare) {
        EXPECT_FLOAT_EQ(set.sun_pdf_pos(0, o, w), on);
      }
    }
    // A line well outside the rectangle: only the scene disk's photons travel along it.
    EXPECT_FLOAT_EQ(set.lp(0, Vec3f(), Vec3f(), sun.axis, Vec3f(0, 6, 0)), scene_disk * pdf_dir);
  }
}

// The host's sharp objects become at most kMaxTargets clusters that enclose every object.
TEST(CausticsEmitters, ClustersEncloseEveryObject) {
  Pcg32 rng(23);
  std::vector<Target> objects;
  for (int i = 0; i < 100; ++i) {
    const Vec3f c(20 * uniform(rng), 20 * uniform(rng), uniform(rng));
    const float r = 0.05f + 0.3f * uniform(rng);
    objects.push_back({{c, r}, c - Vec3f(r), c + Vec3f(r)});
  }
  const std::vector<Target> copy = objects;
  std::vector<Target> clusters;
  cluster(objects, kMaxTargets, clusters);
  EXPECT_EQ(clusters.size(), kMaxTargets);
  for (const Target &o : copy) {
    bool inside = false;
    for (const Target &c : clusters)
      inside =
          inside || length(o.sphere.center - c.sphere.center) + o.sphere.radius <= c.sphere.radius * 1.0001f;
    EXPECT_TRUE(inside);
  }
}

// A photon counts in a pixel's density (pixel_radius.hpp) as the most likely light's selection
// probability over its light's: a light chosen a third as often counts three times, so a focus shrinks the
// kernel alike whichever light forms it; at most kMaxDensityWeight; a light that emits no photon, 0.
TEST(CausticsEmitters, DensityWeightsAreTheMostLikelyShareOverTheLightsOwn) {
  EmitterSet set;
  set.build(three_lights(), Vec3f(0, 0, 0), 10, nullptr, &kStubLights, two_targets());
  set.set_selection({0.6, 0.3, 0.1});
  std::vector<float> w = density_weights(set);
  ASSERT_EQ(w.size(), 3u);
  EXPECT_NEAR(w[0], 1.0f, 1e-6f);
  EXPECT_NEAR(w[1], 2.0f, 1e-5f);
  EXPECT_NEAR(w[2], 6.0f, 1e-5f);
  set.set_selection({0.0, 0.999, 0.001});
  w = density_weights(set);
  EXPECT_EQ(w[0], 0.0f);
  EXPECT_NEAR(w[1], 1.0f, 1e-6f);
  EXPECT_EQ(w[2], kMaxDensityWeight);
}

}  // namespace emitters_test
}  // namespace nimbus::caustics
