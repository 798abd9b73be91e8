// The lights service's eval_emission and pdf_emission against sample_emission, through the C table as
// plugins call it: for photons drawn by sample_emission, pdf_emission at the photon's origin, normal and
// direction returns its pdf_pos and pdf_dir, and eval_emission its Le, for every kind of light. Also:
// the spot's falloff is the one sample_incident applies, and info.area is each emitter's surface area
// (written only into callers whose struct has it).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include <nimbus/cpp/sampling.hpp>
#include "emission_support.hpp"
#include "materials/test_helpers.hpp"

namespace nimbus::testing {
namespace emission_consistency_test {

using test::Pcg32;

// What may differ between a sample and its re-evaluation, per kind of light.
struct Tolerance {
  // pdf_dir: |a - b| <= rel * max(a, b) + abs. Area lights: the cosine is recomputed as dot(n, dir) from
  // a direction that went through the frame of n, ~3 float ulps of 1 (4e-7) in absolute; 1e-6 / pi
  // covers it with room. Elsewhere the density is the same expression of the same constants: exact.
  float pdf_rel = 0, pdf_abs = 0;
  // Le: |a - b| <= le_rel * max(a, b) + le_abs per channel. Spots: the falloff of the recomputed cosine,
  // whose slope is at most 1.5 / (cos(start) - cos(end)) = 9.4 for the test spot: 9.4 x 4e-7 < 1e-5 of
  // the intensity (5 at most).
  float le_rel = 0, le_abs = 0;
  // Share of samples allowed to disagree beyond that. Environment maps: a direction within rounding of
  // a texel edge maps back to the neighbouring texel, and near the poles the sample's sin(theta) (from
  // its v) and the lookup's (from x and y) differ by up to ~1e-3 relative, as for pdf_incident
  // (light_sampling_test.cpp).
  double outlier_share = 0;
};

struct Counts {
  int checked = 0, pdf_outliers = 0, le_outliers = 0;
};

bool close(float a, float b, float rel, float abs) {
  return std::abs(a - b) <= rel * std::max(std::abs(a), std::abs(b)) + abs;
}

// Draws n photons of light `l` and compares each with pdf_emission and eval_emission at its own origin,
// normal and direction. Photons within rounding of a cone's rim (spot, sun: |dot(dir, axis) - cos| <
// 1e-6) may land on either side of it and are not compared.
Counts check_light(const LightsHarness &h, uint32_t l, const Tolerance &tol, int n = 100000) {
  const nimbus_light_info_t info = h.info(l);
  const Vec3f axis = Vec3f::load(info.axis);
  const bool cone = (info.flags & (NIMBUS_LIGHT_AREA | NIMBUS_LIGHT_DELTA_DIRECTION)) == 0 && !is_black(axis);
  Pcg32 rng(101 + l);
  Counts c;
  for (int i = 0; i < n; ++i) {
    const float u[4] = {rng.uniform(), rng.uniform(), rng.uniform(), rng.uniform()};
    const nimbus_light_emission_t es = h.sample(l, u);
    if (!(es.pdf_pos > 0) || !(es.pdf_dir > 0)) continue;
    if (cone && std::abs(dot(Vec3f::load(es.dir), axis) - info.cos_theta_e) < 1e-6f) continue;
    ++c.checked;
    float pdf_pos = -1, pdf_dir = -1;
    h.pdf(l, es, pdf_pos, pdf_dir);
    EXPECT_EQ(pdf_pos, es.pdf_pos) << "light " << l << ": the same expression of the same constants";
    if (!close(pdf_dir, es.pdf_dir, tol.pdf_rel, tol.pdf_abs)) {
      ++c.pdf_outliers;
      if (tol.outlier_share == 0)
        ADD_FAILURE() << "light " << l << ": pdf_dir " << pdf_dir << " for a sample of " << es.pdf_dir;
    }
    const Rgb Le = h.eval(l, es), sampled = Rgb::load(es.Le);
    bool le_ok = true;
    for (int k = 0; k < 3; ++k) le_ok = le_ok && close(Le[k], sampled[k], tol.le_rel, tol.le_abs);
    if (!le_ok) {
      ++c.le_outliers;
      if (tol.outlier_share == 0)
        ADD_FAILURE() << "light " << l << ": Le " << Le[0] << " " << Le[1] << " " << Le[2]
                      << " for a sample of " << sampled[0] << " " << sampled[1] << " " << sampled[2];
    }
    if (c.pdf_outliers + c.le_outliers > 20 && tol.outlier_share == 0) break;  // enough said
  }
  EXPECT_GT(c.checked, n * 9 / 10) << "light " << l << ": most photons are valid and compared";
  EXPECT_LE(c.pdf_outliers, c.checked * tol.outlier_share) << "light " << l;
  EXPECT_LE(c.le_outliers, c.checked * tol.outlier_share) << "light " << l;
  return c;
}

const Tolerance kExact{};
const Tolerance kArea{1e-5f, 1e-6f * kInvPi, 0, 0, 0};
const Tolerance kSpot{0, 0, 0, 5e-5f, 0};
const Tolerance kEnvironment{1e-3f, 0, 1e-3f, 0, 1e-3};

TEST(EmissionConsistency, AreaLightsEvaluateTheirSamples) {
  const LightsHarness h(kAreaScene);
  ASSERT_EQ(h.count(), 4u);
  for (uint32_t l = 0; l < 4; ++l) check_light(h, l, kArea);
}

TEST(EmissionConsistency, PointSpotAndSunsEvaluateTheirSamples) {
  const LightsHarness h(kDeltaScene);
  ASSERT_EQ(h.count(), 4u);
  check_light(h, 0, kExact);
  check_light(h, 1, kSpot);
  check_light(h, 2, kExact);
  check_light(h, 3, kExact);  // a delta direction: pdf_dir 1
}

TEST(EmissionConsistency, EnvironmentsEvaluateTheirSamples) {
  const std::string map = write_environment_map("nimbus_emission_consistency.exr");
  for (const std::string &env : std::vector<std::string>{
           "{ color: [0.5, 0.6, 0.7] }", "{ type: sky, turbidity: 3, sun_direction: [0.3, 0.2, 1] }",
           "{ map: " + map + ", rotate: 30 }"}) {
    const LightsHarness h("environment: " + env + "\n");
    ASSERT_EQ(h.count(), 1u) << env;
    SCOPED_TRACE(env);
    check_light(h, 0, kEnvironment);
  }
  std::filesystem::remove(map);
}

// The spot's falloff: eval_emission along w is the intensity that sample_incident reports (times d^2) at
// a receiver along w, for directions all over the sphere (inside, across and outside the soft edge).
TEST(EmissionConsistency, SpotFalloffIsTheIncidentOne) {
  const LightsHarness h(kDeltaScene);
  const Vec3f position(-0.5f, 0.4f, 1);
  const Vec3f axis = Vec3f::load(h.info(1).axis);
  Pcg32 rng(7);
  int in_soft_edge = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3f w = (i % 2 ? sample_uniform_sphere(rng.uniform(), rng.uniform())
                           : Frame::from_normal(axis).to_world(sample_uniform_cone(
                                 rng.uniform(), rng.uniform(), std::cos(radians(50.0f)))));
    nimbus_interaction_t at{};
    (position + w * 2.0f).store(at.p);
    const float u[2] = {0.5f, 0.5f};
    nimbus_light_incident_t li{};
    h.table().sample_incident(h.host(), 1, &at, u, &li);
    const Rgb incident = Rgb::load(li.L) * sqr(li.dist);
    float p[3], d[3], Le[3];
    position.store(p), w.store(d);
    h.table().eval_emission(h.host(), 1, p, nullptr, d, Le);
    for (int k = 0; k < 3; ++k)
      ASSERT_TRUE(close(Le[k], incident[k], 1e-5f, 1e-5f * 5))
          << Le[k] << " vs " << incident[k] << " along w.z " << dot(w, axis);
    const float c = dot(w, axis);
    in_soft_edge += c > std::cos(radians(45.0f)) && c < std::cos(radians(30.0f));
  }
  EXPECT_GT(in_soft_edge, 1000);
}

TEST(EmissionConsistency, UnknownLightsAndMissingNormalsEmitNothing) {
  const LightsHarness h(kAreaScene);
  const float p[3] = {0, 0, 0}, n[3] = {0, 0, 1}, d[3] = {0, 0, 1};
  float Le[3] = {1, 1, 1}, pdf_pos = 1, pdf_dir = 1;
  h.table().eval_emission(h.host(), 99, p, n, d, Le);
  h.table().pdf_emission(h.host(), 99, p, n, d, &pdf_pos, &pdf_dir);
  EXPECT_EQ(Le[0] + Le[1] + Le[2], 0.0f);
  EXPECT_EQ(pdf_pos + pdf_dir, 0.0f);
  h.table().eval_emission(h.host(), 0, p, nullptr, d, Le);
  h.table().pdf_emission(h.host(), 0, p, nullptr, d, &pdf_pos, &pdf_dir);
  EXPECT_EQ(Le[0] + Le[1] + Le[2], 0.0f);
  EXPECT_EQ(pdf_dir, 0.0f);
  EXPECT_FLOAT_EQ(pdf_pos, 0.5f) << "the rectangle's area is 2";
}

TEST(LightInfo, AreaIsTheEmittersSurfaceArea) {
  const LightsHarness a(kAreaScene);
  const float expected[4] = {2, 4 * kPi * 0.36f, kPi * 0.49f, 2 * (1 * 2 + 2 * 3 + 3 * 1)};
  for (uint32_t l = 0; l < 4; ++l)
    EXPECT_NEAR(a.info(l).area, expected[l], 1e-5f * expected[l]) << "light " << l;
  const LightsHarness d(kDeltaScene);
  for (uint32_t l = 0; l < d.count(); ++l) EXPECT_EQ(d.info(l).area, 0.0f) << "light " << l;
  const LightsHarness e("environment: { color: [1, 1, 1] }\n");
  EXPECT_EQ(e.info(0).area, 0.0f);
}

// Callers built with SDK 1.0 or 1.1 pass the struct without `area`: the host fills their members and
// writes nothing past them. A struct shorter than 1.0's is refused.
TEST(LightInfo, OlderCallersGetTheirMembersOnly) {
  const LightsHarness h(kAreaScene);
  const nimbus_light_info_t full = h.info(1);
  alignas(nimbus_light_info_t) unsigned char buf[sizeof(nimbus_light_info_t) + 8];
  std::memset(buf, 0xAB, sizeof(buf));
  auto *info = reinterpret_cast<nimbus_light_info_t *>(buf);
  info->header = {uint32_t(offsetof(nimbus_light_info_t, area)), 0, nullptr};
  ASSERT_EQ(h.table().info(h.host(), 1, info), NIMBUS_OK);
  EXPECT_EQ(info->header.s_type, NIMBUS_S_TYPE_LIGHT_INFO);
  EXPECT_EQ(info->power, full.power);
  EXPECT_EQ(std::memcmp(&info->cos_theta_e, &full.cos_theta_e, sizeof(float)), 0);
  for (size_t i = offsetof(nimbus_light_info_t, area); i < sizeof(buf); ++i)
    ASSERT_EQ(buf[i], 0xAB) << "byte " << i << " written past the caller's struct";
  info->header.struct_size = uint32_t(offsetof(nimbus_light_info_t, area)) - 1;
  EXPECT_EQ(h.table().info(h.host(), 1, info), NIMBUS_E_INVALID_ARG);
}

}  // namespace emission_consistency_test
}  // namespace nimbus::testing
