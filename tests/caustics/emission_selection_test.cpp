// The solver's light selection for photon emission (emission_selection.hpp): it reports cumulative
// per-light counts to the bound sampler's update_emission and freezes its pmf_emitter; a sampler built
// before SDK 1.6 gets the kit's rule inside the solver; probabilities outside [0, 1] are errors, not
// photons;
// the counts survive the state's round trip.
#include <gtest/gtest.h>

#include <vector>

#include "emission_selection.hpp"
#include "lights/emission_support.hpp"
#include "state_bytes.hpp"

namespace nimbus::caustics {
namespace emission_selection_test {

// A sampler table whose update_emission keeps a copy of what it was told and whose pmf_emitter returns
// g_pmf.
struct Told {
  int calls = 0;
  uint32_t flags = 0;
  std::vector<double> power;
  std::vector<uint64_t> emitted, contributed;
  float camera[3] = {};
} g_told;
std::vector<float> g_pmf;

nimbus_light_sampler_v1_t feedback_sampler() {
  nimbus_light_sampler_v1_t t{};
  t.struct_size = sizeof(t);
  t.update_emission = [](const nimbus_plugin_t *, const nimbus_emission_feedback_t *f) {
    ++g_told.calls, g_told.flags = f->flags;
    g_told.power.assign(f->photon_power, f->photon_power + f->light_count);
    g_told.emitted.assign(f->emitted, f->emitted + f->light_count);
    g_told.contributed.assign(f->contributed, f->contributed + f->light_count);
    for (int k = 0; k < 3; ++k) g_told.camera[k] = f->camera[k];
    return NIMBUS_OK;
  };
  t.pmf_emitter = [](const nimbus_plugin_t *, uint32_t l) { return l < g_pmf.size() ? g_pmf[l] : 0.0f; };
  return t;
}

constexpr const char *kTwoLamps = R"(
camera: { position: [0, -5, 1], look_at: [0, 0, 1] }
materials:
  white: { type: diffuse, albedo: [0.5, 0.5, 0.5] }
objects:
  - { shape: rectangle, size: [40, 40], material: white }
lights:
  - { type: point, position: [0, -4, 1], power: 10 }
  - { type: point, position: [0, 5, 1], power: 40 }
)";

EmissionSelection::Inputs inputs(bool lightmix = false, bool power_only = false) {
  return {{10.0, 40.0}, Vec3f(0, -5, 1), 30.0f, lightmix, power_only};
}

TEST(CausticsEmissionSelection, ReportsCumulativeCountsToTheSamplerAndFreezesItsTable) {
  testing::LightsHarness scene(kTwoLamps);
  const nimbus_light_sampler_v1_t table = feedback_sampler();
  EmissionSelection s;
  ASSERT_EQ(s.configure(nullptr, &table, scene.host(), &scene.table(), inputs(true)), NIMBUS_OK);
  EXPECT_TRUE(s.by_sampler());
  g_told = {}, g_pmf = {0.3f, 0.7f};
  std::vector<double> p;
  std::string error;
  ASSERT_EQ(s.probabilities(p, error), NIMBUS_OK) << error;
  EXPECT_EQ(p, (std::vector<double>{double(0.3f), double(0.7f)}));
  EXPECT_EQ(g_told.flags, NIMBUS_EMISSION_LIGHTMIX);
  EXPECT_EQ(g_told.power, (std::vector<double>{10.0, 40.0}));
  EXPECT_EQ(g_told.camera[1], -5.0f);
  EXPECT_EQ(g_told.emitted, (std::vector<uint64_t>{0, 0}));
  for (int pass = 0; pass < 2; ++pass)
    for (int i = 0; i < 10; ++i) s.count(i % 2, i < 3);
  ASSERT_EQ(s.probabilities(p, error), NIMBUS_OK) << error;
  EXPECT_EQ(g_told.calls, 2);
  EXPECT_EQ(g_told.emitted, (std::vector<uint64_t>{10, 10}));  // over both passes
  EXPECT_EQ(g_told.contributed, (std::vector<uint64_t>{4, 2}));

  // A light the table never picks (below its resolution) gets no photons, on both sides.
  g_pmf = {0.0f, 1.0f};
  ASSERT_EQ(s.probabilities(p, error), NIMBUS_OK) << error;
  EXPECT_EQ(p, (std::vector<double>{0.0, 1.0}));
  // What no photon map may be traced with.
  g_pmf = {std::nanf(""), 1.0f};
  EXPECT_NE(s.probabilities(p, error), NIMBUS_OK);
  EXPECT_NE(error.find("light 0"), std::string::npos) << error;
  g_pmf = {0.5f, 1.5f};
  EXPECT_NE(s.probabilities(p, error), NIMBUS_OK);
}

TEST(CausticsEmissionSelection, OlderSamplersGetTheKitsRuleAndPowerSelectionAsksNoSampler) {
  testing::LightsHarness scene(kTwoLamps);
  // A sampler built against SDK 1.5: its table ends before update_emission.
  nimbus_light_sampler_v1_t old = feedback_sampler();
  old.struct_size = offsetof(nimbus_light_sampler_v1_t, update_emission);
  g_told = {};
  EmissionSelection s;
  ASSERT_EQ(s.configure(nullptr, &old, scene.host(), &scene.table(), inputs()), NIMBUS_OK);
  EXPECT_FALSE(s.by_sampler());
  std::vector<double> p;
  std::string error;
  ASSERT_EQ(s.probabilities(p, error), NIMBUS_OK) << error;
  EXPECT_EQ(g_told.calls, 0);
  // The kit's prior: 10 / 1^2 against 40 / 10^2.
  EXPECT_NEAR(p[0], 10.0 / 10.4, 1e-6);
  EXPECT_NEAR(p[1], 0.4 / 10.4, 1e-6);

  const nimbus_light_sampler_v1_t table = feedback_sampler();
  EmissionSelection power;
  ASSERT_EQ(power.configure(nullptr, &table, scene.host(), &scene.table(), inputs(false, true)), NIMBUS_OK);
  EXPECT_FALSE(power.by_sampler());
  ASSERT_EQ(power.probabilities(p, error), NIMBUS_OK);
  EXPECT_EQ(p, (std::vector<double>{10.0, 40.0}));
  EXPECT_EQ(g_told.calls, 0);
}

TEST(CausticsEmissionSelection, StateRoundTripsAndRejectsImpossibleCounts) {
  testing::LightsHarness scene(kTwoLamps);
  const nimbus_light_sampler_v1_t table = feedback_sampler();
  EmissionSelection s;
  ASSERT_EQ(s.configure(nullptr, &table, scene.host(), &scene.table(), inputs()), NIMBUS_OK);
  for (int i = 0; i < 50; ++i) s.count(i % 2, i % 3 == 0);
  Bytes b;
  s.save(b);
  EmissionSelection back;
  ASSERT_EQ(back.configure(nullptr, &table, scene.host(), &scene.table(), inputs()), NIMBUS_OK);
  ASSERT_TRUE(back.restore(b));
  g_pmf = {0.5f, 0.5f};
  std::vector<double> p;
  std::string error;
  ASSERT_EQ(back.probabilities(p, error), NIMBUS_OK);
  EXPECT_EQ(g_told.emitted, (std::vector<uint64_t>{25, 25}));
  EXPECT_EQ(g_told.contributed, (std::vector<uint64_t>{9, 8}));
  Bytes bad;
  bad.put(uint64_t(2)), bad.put(uint64_t(5)), bad.put(uint64_t(6)), bad.put(uint64_t(1)),
      bad.put(uint64_t(0));
  EXPECT_FALSE(back.restore(bad));  // 6 of 5 paths contributed
  ASSERT_EQ(back.probabilities(p, error), NIMBUS_OK);
  EXPECT_EQ(g_told.emitted, (std::vector<uint64_t>{25, 25})) << "a refused state changes nothing";
  Bytes wrong_size;
  wrong_size.put(uint64_t(3));
  EXPECT_FALSE(back.restore(wrong_size));
}

}  // namespace emission_selection_test
}  // namespace nimbus::caustics
