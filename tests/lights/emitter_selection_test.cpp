// Light selection for photon emission (the SDK kit's emitter_selection.hpp, solver spec 6.1) against the
// rule computed by hand: the prior's group split and camera-distance weights (from a scene's lights as
// the host describes them), the shrinkage of the adaptation, the defensive share that keeps a light that
// never contributed reachable, LightMix's balance over groups, and feedback that does not fit.
#include <gtest/gtest.h>

#include <numeric>

#include <nimbus/cpp/emitter_selection.hpp>
#include "emission_support.hpp"

namespace nimbus::testing {
namespace emitter_selection_test {

using Light = sdk::EmitterSelection::Light;

double sum(const std::vector<double> &p) { return std::accumulate(p.begin(), p.end(), 0.0); }

TEST(EmitterSelection, PriorSplitsGroupsAndWeighsFiniteLightsByCameraDistance) {
  // Two finite lights of equal power at distances 1 and 10, a sun of any power, and a dark light.
  const std::vector<Light> lights = {
      {100, false, 1, 0}, {100, false, 100, 0}, {5, true, 1, 0}, {0, false, 1, 0}};
  const std::vector<double> p = sdk::EmitterSelection::probabilities(lights, nullptr, nullptr, false);
  EXPECT_NEAR(sum(p), 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(p[2], 0.5);                    // group I
  EXPECT_NEAR(p[0], 0.5 * 100.0 / 101.0, 1e-12);  // 1/1 against 1/100
  EXPECT_NEAR(p[1], 0.5 * 1.0 / 101.0, 1e-12);
  EXPECT_EQ(p[3], 0.0);
  // Without infinite lights the finite ones take everything.
  const std::vector<double> f =
      sdk::EmitterSelection::probabilities({{1, false, 4, 0}, {3, false, 4, 0}}, nullptr, nullptr, false);
  EXPECT_NEAR(f[1], 0.75, 1e-12);
}

TEST(EmitterSelection, AdaptationShrinksCountsAndKeepsADefensiveShare) {
  const std::vector<Light> lights(3, Light{1, false, 1, 0});
  // Light 0: 1000 paths, 300 contributed; light 1: 1000, none; light 2: never sampled.
  const uint64_t n[3] = {1000, 1000, 0}, c[3] = {300, 0, 0};
  const std::vector<double> p = sdk::EmitterSelection::probabilities(lights, n, c, false);
  const double mean = 300.0 / 2000.0, p0 = 1.0 / 3.0;
  const double s0 = (300 + mean) / 1001, s1 = mean / 1001, s2 = mean / 1;
  const double norm = p0 * (s0 + s1 + s2);
  EXPECT_NEAR(p[0], 0.8 * p0 * s0 / norm + 0.2 * p0, 1e-12);
  EXPECT_NEAR(p[1], 0.8 * p0 * s1 / norm + 0.2 * p0, 1e-12);
  EXPECT_NEAR(p[2], 0.8 * p0 * s2 / norm + 0.2 * p0, 1e-12);
  EXPECT_GE(p[1], 0.2 * p0);  // never below the defensive share
  EXPECT_NEAR(sum(p), 1.0, 1e-12);
  // Nothing contributed yet: the prior.
  const uint64_t idle_n[2] = {100, 0}, idle_c[2] = {0, 0};
  EXPECT_NEAR(
      sdk::EmitterSelection::probabilities({{1, false, 1, 0}, {3, false, 1, 0}}, idle_n, idle_c, false)[0],
      0.25, 1e-12);
}

// The defensive share weighs each finite light's whole power where the integrator's photon power counts
// less of it (a lamp that sees the sharp objects small): P = 0.8 P0 (s ...) + 0.2 D, D the prior by whole
// power; a light without photon power gets nothing, whatever it emits.
TEST(EmitterSelection, DefensiveShareFollowsTheWholePower) {
  // photon power 1 and 1e-3 (whole 1 and 10) at equal distance, and a light whose photons reach nothing.
  const std::vector<Light> lights = {{1, false, 1, 0, 1}, {1e-3, false, 1, 0, 10}, {0, false, 1, 0, 50}};
  const std::vector<double> p = sdk::EmitterSelection::probabilities(lights, nullptr, nullptr, false);
  const double p0[2] = {1 / 1.001, 1e-3 / 1.001}, d[2] = {1.0 / 11, 10.0 / 11};
  EXPECT_NEAR(p[0], 0.8 * p0[0] + 0.2 * d[0], 1e-12);
  EXPECT_NEAR(p[1], 0.8 * p0[1] + 0.2 * d[1], 1e-12);
  EXPECT_EQ(p[2], 0.0);
  EXPECT_NEAR(sum(p), 1.0, 1e-12);
  // With counts: the adapted 80 % follows the photon power, the defensive 20 % the whole power.
  const uint64_t n[3] = {1000, 1000, 0}, c[3] = {500, 500, 0};
  const std::vector<double> q = sdk::EmitterSelection::probabilities(lights, n, c, false);
  EXPECT_NEAR(q[1], 0.8 * p0[1] + 0.2 * d[1], 1e-12);  // equal usefulness: the prior's split
}

TEST(EmitterSelection, LightMixGivesEveryGroupHalfItsFairShare) {
  // Group 0 holds a light 10^6 times brighter than group 1's.
  const std::vector<double> p =
      sdk::EmitterSelection::probabilities({{1e6, false, 1, 0}, {1, false, 1, 1}}, nullptr, nullptr, true);
  EXPECT_NEAR(sum(p), 1.0, 1e-12);
  EXPECT_GE(p[1], 0.25);  // half of the paths are shared uniformly over the two groups
}

// A sampler's table from the host's lights: by power before any feedback, then by the rule, with each
// finite light's distance measured from the camera to its bounds.
TEST(EmitterSelection, FollowsFeedbackWithDistancesFromTheHostsLights) {
  LightsHarness scene(R"(
camera: { position: [0, -5, 1], look_at: [0, 0, 1] }
materials:
  white: { type: diffuse, albedo: [0.5, 0.5, 0.5] }
objects:
  - { shape: rectangle, size: [40, 40], material: white }
lights:
  - { type: point, position: [0, -4, 1], power: 10 }
  - { type: point, position: [0, 5, 1], power: 40 }
  - { type: sun, direction: [0, 0, -1], irradiance: 2 }
)");
  ASSERT_EQ(scene.count(), 3u);
  sdk::EmitterSelection s;
  nimbus_scene_info_t info{};
  info.header = {sizeof(info), NIMBUS_S_TYPE_SCENE_INFO, nullptr};
  info.light_count = 3, info.scene_radius = 30;
  ASSERT_EQ(s.prepare(scene.host(), &scene.table(), info), NIMBUS_OK);
  double total = 0;
  for (uint32_t l = 0; l < 3; ++l) total += scene.info(l).power;
  EXPECT_NEAR(s.pmf(1), scene.info(1).power / total, 1e-6) << "by power before any feedback";

  // Photon powers 10, 40 and 7 (the solver's own, pruned); the camera at distances 1 and 10.
  const double power[3] = {10, 40, 7};
  const uint64_t n[3] = {0, 0, 0}, c[3] = {0, 0, 0};
  nimbus_emission_feedback_t f{};
  f.header = {sizeof(f), NIMBUS_S_TYPE_EMISSION_FEEDBACK, nullptr};
  f.light_count = 3, f.camera[1] = -5, f.camera[2] = 1;
  f.photon_power = power, f.emitted = n, f.contributed = c;
  ASSERT_EQ(s.update(f), NIMBUS_OK);
  const double near = 10.0 / 1.0, far = 40.0 / 100.0;
  EXPECT_NEAR(s.pmf(0), 0.5 * near / (near + far), 1e-6);
  EXPECT_NEAR(s.pmf(1), 0.5 * far / (near + far), 1e-6);
  EXPECT_NEAR(s.pmf(2), 0.5, 1e-6);
  float pmf = 0;
  EXPECT_EQ(s.pick(0.9999f, &pmf) == NIMBUS_NONE, false);
  EXPECT_GT(pmf, 0.0f);
  // Feedback for another scene's lights is refused and leaves the table as it was.
  f.light_count = 2;
  EXPECT_EQ(s.update(f), NIMBUS_E_INVALID_ARG);
  EXPECT_NEAR(s.pmf(2), 0.5, 1e-6);
}

}  // namespace emitter_selection_test
}  // namespace nimbus::testing
