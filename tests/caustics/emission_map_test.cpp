// The adaptive emission map (emission_map.hpp) and its use in the projection maps (emitters.hpp): the
// inversions that let the camera side evaluate it, its warp against its pdf (chi-square), that counting
// used paths by 1 / density undoes the density that drew them, its state, and that a light's sampled
// directions and origins follow the density the camera side evaluates once a slot has learnt.
#include <gtest/gtest.h>

#include <cmath>

#include "chi_square.hpp"
#include "emitters.hpp"
#include "state_bytes.hpp"

namespace nimbus::caustics {
namespace emission_map_test {

using test::ChiSquareConfig;
using test::Pcg32;

// A point light (uniform directions) and a sun (a delta direction), as the lights service reports them.
const nimbus_host_lights_v1_t kStubLights = [] {
  nimbus_host_lights_v1_t t{};
  t.struct_size = sizeof(t);
  t.pdf_emission = [](const nimbus_host_t *, uint32_t, const float *, const float *, const float *,
                      float *pdf_pos, float *pdf_dir) { *pdf_pos = 1, *pdf_dir = kUniformSpherePdf; };
  return t;
}();

// An emission map with one learnt slot of 2: used paths in a corner blob and along a stripe.
EmissionMap learnt_map() {
  EmissionMap m;
  m.configure(2, true);
  for (uint32_t i = 0; i < 40; ++i) {
    const uint32_t x = i % 3, y = i % 4;
    m.count(0 * EmissionMap::kCells + y * EmissionMap::kSide + x, true);
    m.count(0 * EmissionMap::kCells + 9 * EmissionMap::kSide + (i % EmissionMap::kSide), i % 2 == 0);
  }
  m.update();
  return m;
}

TEST(CausticsEmissionMap, InversionsRoundTrip) {
  Pcg32 rng(3);
  for (int i = 0; i < 100000; ++i) {
    const float u0 = rng.uniform(), u1 = rng.uniform();
    const Vec2f back = invert_uniform_disk_concentric(sample_uniform_disk_concentric(u0, u1));
    ASSERT_NEAR(back.x, u0, 2e-5f) << u0 << " " << u1;
    ASSERT_NEAR(back.y, u1, 2e-5f) << u0 << " " << u1;
  }
  // Cones from ~80 degrees down to a 5 cm ball 1 km away, around a tilted axis.
  for (const float dist : {0.6f, 3.0f, 1e3f}) {
    const Vec3f center = normalize(Vec3f(0.4f, 0.7f, -0.6f)) * dist;
    const EmissionCone cone = EmissionCone::towards(Vec3f(0, 0, 0), center, dist < 1 ? 0.59f : 0.05f);
    for (int i = 0; i < 20000; ++i) {
      const float u0 = rng.uniform(), u1 = rng.uniform();
      const Vec2f back = cone.invert(cone.sample(u0, u1));
      // 1 - cos theta of a narrow cone carries float's relative error of the direction: at 2e4 times the
      // ball's radius, ~5 % of a map cell (then a photon near a cell's edge may be weighed by its
      // neighbour's density; the tent blur keeps neighbours within a small factor).
      ASSERT_NEAR(back.x, u0, dist > 100 ? 5e-3f : 2e-4f) << dist << ": " << u0 << " " << u1;
      // phi is undefined on the axis: compare it only away from it.
      if (u0 > 0.01f) {
        ASSERT_NEAR(std::remainder(back.y - u1, 1.0f), 0.0f, 2e-3f) << dist << ": " << u0;
      }
    }
  }
}

// The warp's samples, in 64 x 64 cells (4 x 4 per histogram cell: uniform within each), against the pdf;
// the pdf is positive everywhere (the defensive share) and integrates to 1; the unlearnt slot is uniform.
TEST(CausticsEmissionMap, WarpMatchesItsPdf) {
  const EmissionMap m = learnt_map();
  ASSERT_TRUE(m.learnt(0));
  ASSERT_FALSE(m.learnt(1));
  constexpr int kGrid = 64, kSamples = 1'000'000;
  std::vector<double> observed(kGrid * kGrid, 0), expected(kGrid * kGrid, 0);
  double integral = 0, lowest = 1e30, highest = 0;
  for (int y = 0; y < kGrid; ++y)
    for (int x = 0; x < kGrid; ++x) {
      const float p = m.pdf(0, (float(x) + 0.5f) / kGrid, (float(y) + 0.5f) / kGrid);
      expected[size_t(y * kGrid + x)] = double(p) * kSamples / (kGrid * kGrid);
      integral += double(p) / (kGrid * kGrid);
      lowest = std::min(lowest, double(p)), highest = std::max(highest, double(p));
    }
  Pcg32 rng(11);
  for (int i = 0; i < kSamples; ++i) {
    float u0 = rng.uniform(), u1 = rng.uniform();
    const uint32_t code = m.warp(0, u0, u1);
    ASSERT_EQ(code % EmissionMap::kCells,
              uint32_t(u1 * EmissionMap::kSide) * EmissionMap::kSide + uint32_t(u0 * EmissionMap::kSide));
    observed[size_t(int(u1 * kGrid) * kGrid + int(u0 * kGrid))] += 1;
  }
  const test::ChiSquareResult r = test::chi_square_counts(observed, expected, 5);
  EXPECT_TRUE(r.error.empty()) << r.error;
  EXPECT_GT(r.p_value, 0.01) << r.describe();
  EXPECT_NEAR(integral, 1.0, 1e-5);
  EXPECT_GE(lowest, EmissionMap::kDefensive * 0.999) << "every number keeps the defensive density";
  EXPECT_GT(highest, 10.0) << "the used corner is learnt";
  float u0 = 0.3f, u1 = 0.7f;
  EXPECT_EQ(m.warp(1, u0, u1), EmissionMap::kCells + 11 * EmissionMap::kSide + 4);
  EXPECT_EQ(u0, 0.3f);
  EXPECT_EQ(m.pdf(1, 0.3f, 0.7f), 1.0f);
}

// Paths drawn from a learnt density, all of them used (usefulness uniform over the square): weighing
// each by 1 / its density makes the next density uniform again (up to noise); counting them plainly
// would make it the drawing density's, which the last check shows.
TEST(CausticsEmissionMap, CountingUndoesTheDensityThatDrewThePaths) {
  EmissionMap m = learnt_map();
  const EmissionMap before = m;
  Pcg32 rng(5);
  constexpr int kPaths = 2'000'000;
  for (int i = 0; i < kPaths; ++i) {
    float u0 = rng.uniform(), u1 = rng.uniform();
    m.count(m.warp(0, u0, u1), true);
  }
  m.update();
  // The first 60 used paths weigh ~3e-5 of the total. A cell's weight sums >= ~1,950 draws of 1 / p
  // (cells at the defensive density draw the fewest): relative error <= 2.3 %, which the tent blur
  // averages over nine cells (/ ~2.5) and the defensive mix scales by 0.75: sigma <= 0.7 %, so 0.06
  // is over 8 sigma.
  for (uint32_t c = 0; c < EmissionMap::kCells; ++c) {
    const float u0 = (float(c % EmissionMap::kSide) + 0.5f) / EmissionMap::kSide;
    const float u1 = (float(c / EmissionMap::kSide) + 0.5f) / EmissionMap::kSide;
    ASSERT_NEAR(m.pdf(0, u0, u1), 1.0, 0.06) << "cell " << c << ", drawn with " << before.pdf(0, u0, u1);
  }
  EXPECT_GT(before.pdf(0, 0.5f / 16, 0.5f / 16), 5.0f);
}

TEST(CausticsEmissionMap, StateRestoresTheSameDensities) {
  Bytes bytes;
  const EmissionMap m = learnt_map();
  m.save(bytes);
  EmissionMap r;
  r.configure(2, true);
  ASSERT_TRUE(r.restore(bytes));
  r.update();
  for (float u = 0.01f; u < 1; u += 0.037f) ASSERT_EQ(r.pdf(0, u, 1 - u), m.pdf(0, u, 1 - u));
  EmissionMap wrong;
  wrong.configure(0, true);  // another scene's slots
  bytes.read = 0;
  EXPECT_FALSE(wrong.restore(bytes));
  EmissionMap off;
  off.configure(2, false);
  bytes.read = 0;
  EXPECT_FALSE(off.restore(bytes));
}

// A light and a ball: a point light's cone and a sun's disk, each with a learnt slot. The directions
// (origins) the photon side samples follow the density the camera side evaluates.
TEST(CausticsEmissionMap, LearntProjectionMapsMatchTheirDensities) {
  std::vector<Emitter> lights(2);
  lights[0].kind = EmitterKind::Point, lights[0].power = 1;
  lights[0].lo = lights[0].hi = lights[0].position = Vec3f(-2, 0, 1.5f);
  lights[1].kind = EmitterKind::Sun, lights[1].power = 1, lights[1].axis = normalize(Vec3f(1, 0.3f, -1));
  lights[1].flags = NIMBUS_LIGHT_INFINITE | NIMBUS_LIGHT_DELTA_DIRECTION;
  SharpTargets t;
  const Vec3f ball(0.2f, 0.1f, 0.5f);
  t.clusters = {{{ball, 0.5f}, ball - Vec3f(0.5f), ball + Vec3f(0.5f)}};
  t.all = t.clusters[0];
  EmitterSet set;
  set.build(lights, Vec3f(0, 0, 0), 20, nullptr, &kStubLights, t);
  ASSERT_EQ(set[0].aims.size(), 1u);
  ASSERT_FALSE(set[1].use_rect) << "a ball's disk is smaller than its box's rectangle";
  set.reset_emission_map(true);
  EmissionMap &m = set.emission_map();
  for (uint32_t i = 0; i < 30; ++i)
    for (uint32_t slot : {set[0].first_slot, set[1].first_slot})
      m.count(slot * EmissionMap::kCells + (3 + i % 2) * EmissionMap::kSide + 12 + i % 3, true);
  m.update();
  ASSERT_TRUE(m.learnt(set[0].first_slot) && m.learnt(set[1].first_slot));

  const Vec3f z = set[0].position;
  ChiSquareConfig cfg;
  cfg.seed = 21;
  const auto result = test::chi_square_test(
      [&](Pcg32 &rng) -> std::optional<Vec3f> {
        const float um = rng.uniform(), u0 = rng.uniform(), u1 = rng.uniform();
        return set.sample_direction(0, z, um, u0, u1, sample_uniform_sphere(rng.uniform(), rng.uniform()));
      },
      [&](const Vec3f &w) { return double(set.pdf_dir(0, z, w, kUniformSpherePdf)); }, cfg);
  EXPECT_TRUE(result.error.empty()) << result.error;
  EXPECT_GT(result.p_value, 0.01) << result.describe();
  EXPECT_NEAR(result.pdf_integral, 1.0, 5e-3) << result.describe();

  // The sun's origins: the density at an origin is the one its numbers were warped with (but where
  // float rounding puts an origin within ~1e-6 of a cell's edge, on the other side: rare).
  Pcg32 rng(8);
  int other_cell = 0;
  const Vec3f w = set[1].axis;
  const float scene_disk = set[1].own / (kPi * 20 * 20);
  for (int i = 0; i < 20000; ++i) {
    float u0 = rng.uniform(), u1 = rng.uniform();
    const Vec3f o = set.emission_origin(1, w, 0.99f, u0, u1);
    float v0 = u0, v1 = u1;
    m.warp(set[1].first_slot, v0, v1);
    const float expected = scene_disk + (1 - set[1].own) * set[1].pdf_pos * m.pdf(set[1].first_slot, v0, v1);
    other_cell += std::abs(set.sun_pdf_pos(1, o + w * 30.0f, w) - expected) > 1e-4f * expected ? 1 : 0;
  }
  EXPECT_LE(other_cell, 20);
}

}  // namespace emission_map_test
}  // namespace nimbus::caustics
