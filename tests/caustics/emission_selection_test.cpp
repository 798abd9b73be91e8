// Light selection for photon emission (emission_selection.hpp, spec 6.1) against the rule computed by
// hand: the prior's group split and camera-distance weights, the shrinkage of the adaptation, the
// defensive share that keeps a light that never contributed reachable, LightMix's balance over groups,
// and the state's round trip.
#include <gtest/gtest.h>

#include <numeric>

#include "emission_selection.hpp"
#include "state_bytes.hpp"

namespace nimbus::caustics {
namespace {

double sum(const std::vector<double> &p) { return std::accumulate(p.begin(), p.end(), 0.0); }

TEST(CausticsEmissionSelection, PriorSplitsGroupsAndWeighsFiniteLightsByCameraDistance) {
  EmissionSelection s;
  // Two finite lights of equal power at distances 1 and 10, a sun of any power, and a dark light.
  s.configure({{100, false, 1, 0}, {100, false, 100, 0}, {5, true, 1, 0}, {0, false, 1, 0}}, false);
  const std::vector<double> p = s.probabilities();
  EXPECT_NEAR(sum(p), 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(p[2], 0.5);                    // group I
  EXPECT_NEAR(p[0], 0.5 * 100.0 / 101.0, 1e-12);  // 1/1 against 1/100
  EXPECT_NEAR(p[1], 0.5 * 1.0 / 101.0, 1e-12);
  EXPECT_EQ(p[3], 0.0);
  // Without infinite lights the finite ones take everything.
  EmissionSelection f;
  f.configure({{1, false, 4, 0}, {3, false, 4, 0}}, false);
  EXPECT_NEAR(f.probabilities()[1], 0.75, 1e-12);
  // The measurement option: photon power alone, whatever the camera sees or the photons did.
  EmissionSelection power;
  power.configure({{100, false, 1, 0}, {100, false, 100, 0}, {5, true, 1, 0}}, false, false);
  for (int i = 0; i < 100; ++i) power.count(0, true), power.count(1, false);
  EXPECT_NEAR(power.probabilities()[0], 100.0 / 205.0, 1e-12);
  EXPECT_NEAR(power.probabilities()[2], 5.0 / 205.0, 1e-12);
}

TEST(CausticsEmissionSelection, AdaptationShrinksCountsAndKeepsADefensiveShare) {
  EmissionSelection s;
  s.configure({{1, false, 1, 0}, {1, false, 1, 0}, {1, false, 1, 0}}, false);
  // Light 0: 1000 paths, 300 contributed; light 1: 1000, none; light 2: never sampled.
  for (int i = 0; i < 1000; ++i) s.count(0, i < 300), s.count(1, false);
  const std::vector<double> p = s.probabilities();
  const double mean = 300.0 / 2000.0, p0 = 1.0 / 3.0;
  const double s0 = (300 + mean) / 1001, s1 = mean / 1001, s2 = mean / 1;
  const double norm = p0 * (s0 + s1 + s2);
  EXPECT_NEAR(p[0], 0.8 * p0 * s0 / norm + 0.2 * p0, 1e-12);
  EXPECT_NEAR(p[1], 0.8 * p0 * s1 / norm + 0.2 * p0, 1e-12);
  EXPECT_NEAR(p[2], 0.8 * p0 * s2 / norm + 0.2 * p0, 1e-12);
  EXPECT_GE(p[1], 0.2 * p0);  // never below the defensive share
  EXPECT_NEAR(sum(p), 1.0, 1e-12);
  // Nothing contributed yet: the prior.
  EmissionSelection idle;
  idle.configure({{1, false, 1, 0}, {3, false, 1, 0}}, false);
  for (int i = 0; i < 100; ++i) idle.count(0, false);
  EXPECT_NEAR(idle.probabilities()[0], 0.25, 1e-12);
}

TEST(CausticsEmissionSelection, LightMixGivesEveryGroupHalfItsFairShare) {
  EmissionSelection s;
  // Group 0 holds a light 10^6 times brighter than group 1's.
  s.configure({{1e6, false, 1, 0}, {1, false, 1, 1}}, true);
  const std::vector<double> p = s.probabilities();
  EXPECT_NEAR(sum(p), 1.0, 1e-12);
  EXPECT_GE(p[1], 0.25);  // half of the paths are shared uniformly over the two groups
}

TEST(CausticsEmissionSelection, StateRoundTripsAndRejectsImpossibleCounts) {
  EmissionSelection s;
  s.configure({{1, false, 1, 0}, {2, true, 1, 0}}, false);
  for (int i = 0; i < 50; ++i) s.count(i % 2, i % 3 == 0);
  Bytes b;
  s.save(b);
  EmissionSelection back;
  back.configure({{1, false, 1, 0}, {2, true, 1, 0}}, false);
  ASSERT_TRUE(back.restore(b));
  EXPECT_EQ(back.probabilities(), s.probabilities());
  Bytes bad;
  bad.put(uint64_t(2)), bad.put(uint64_t(5)), bad.put(uint64_t(6)), bad.put(uint64_t(1)),
      bad.put(uint64_t(0));
  EmissionSelection untouched = back;
  EXPECT_FALSE(untouched.restore(bad));  // 6 of 5 paths contributed
  EXPECT_EQ(untouched.probabilities(), s.probabilities());
  Bytes wrong_size;
  wrong_size.put(uint64_t(3));
  EXPECT_FALSE(untouched.restore(wrong_size));
}

}  // namespace
}  // namespace nimbus::caustics
