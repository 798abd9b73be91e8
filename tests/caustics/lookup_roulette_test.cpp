// The lookup roulette (lookup_roulette.hpp): its updates reach the later lookups' probability that
// minimises variance x work of the model they assume, found here by brute force; later lookups that carry
// no light fall to the floor; lookups at the first rough vertex always happen, however little they seem
// to carry; its state survives a save and a restore and rejects values out of range.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "lookup_roulette.hpp"
#include "state_bytes.hpp"

namespace nimbus::caustics {
namespace lookup_roulette_test {

// A camera pass of the model: V = V_o + sum M_c / q_c, W = W_o + sum q_c w_c.
struct Model {
  double v_other, w_other;
  std::array<double, kLookupClasses> moment, work;

  RouletteSample sample(const LookupRoulette &r) const {
    RouletteSample s{v_other, moment, w_other, {}};
    for (uint32_t c = 0; c < kLookupClasses; ++c) {
      const double q = r.probability(LookupClass(c));
      s.variance += moment[c] / q;
      s.lookup_work[c] = q * work[c];
    }
    return s;
  }
  double cost(double q0, double q1) const {
    return (v_other + moment[0] / q0 + moment[1] / q1) * (w_other + q0 * work[0] + q1 * work[1]);
  }
};

LookupRoulette converge(const Model &m, int updates = 200) {
  LookupRoulette r;
  for (int i = 0; i < updates; ++i) r.update(m.sample(r));
  return r;
}

TEST(CausticsLookupRoulette, ReachesTheProbabilitiesThatMinimiseVarianceTimesWork) {
  const std::vector<Model> models = {
      {1.0, 10.0, {0.05, 0.002}, {2.0, 4.0}},  // a point-lit box: later lookups costly, nearly idle
      {1.0, 10.0, {0.3, 0.08}, {1.0, 3.0}},    // both classes interior optima
      {0.2, 5.0, {0.02, 0.01}, {0.5, 6.0}},
  };
  for (const Model &m : models) {
    const LookupRoulette r = converge(m);
    // Brute force over a fine log grid of [kMinLookupProbability, 1], the first class at 1.
    double best = 1e300, b1 = 1;
    const int n = 4000;
    for (int j = 0; j <= n; ++j) {
      const double q1 = std::exp(std::log(kMinLookupProbability) * (1 - double(j) / n));
      if (const double c = m.cost(1, q1); c < best) best = c, b1 = q1;
    }
    const double q0 = r.probability(kFirstLookup), q1 = r.probability(kLaterLookup);
    EXPECT_EQ(q0, 1.0f) << "first-vertex class";
    EXPECT_NEAR(q1, b1, 0.02 * b1) << "later class";
    EXPECT_LE(m.cost(q0, q1), best * (1 + 1e-4));
  }
}

TEST(CausticsLookupRoulette, IdleLookupsFallToTheFloorAndLightCarryingOnesStayAtOne) {
  // Later lookups find nothing (second moment 0); first-vertex lookups carry most of the variance.
  const LookupRoulette r = converge({0.01, 10.0, {5.0, 0.0}, {1.0, 4.0}});
  EXPECT_FLOAT_EQ(r.probability(kFirstLookup), 1.0f);
  EXPECT_NEAR(r.probability(kLaterLookup), kMinLookupProbability, 1e-5);
}

TEST(CausticsLookupRoulette, FirstVertexLookupsAlwaysHappen) {
  // First-vertex lookups that seem to carry almost nothing, at a high cost (the model's optimum for them
  // would be the floor): they still happen at every first rough vertex.
  const LookupRoulette r = converge({1.0, 10.0, {1e-6, 0.002}, {8.0, 4.0}});
  EXPECT_EQ(r.probability(kFirstLookup), 1.0f);
  EXPECT_LT(r.probability(kLaterLookup), 0.5f);
}

TEST(CausticsLookupRoulette, UnmeasuredClassesKeepTheirProbability) {
  LookupRoulette r;
  // No lookup of either class happened, or no variance was measured: nothing is learnt.
  r.update(RouletteSample{1.0, {0.5, 0.5}, 10.0, {0.0, 0.0}});
  r.update(RouletteSample{0.0, {0.5, 0.5}, 10.0, {1.0, 1.0}});
  EXPECT_EQ(r.probability(kFirstLookup), 1.0f);
  EXPECT_EQ(r.probability(kLaterLookup), 1.0f);
}

TEST(CausticsLookupRoulette, StateRoundTripsAndRejectsOutOfRangeValues) {
  const LookupRoulette r = converge({1.0, 10.0, {0.05, 0.002}, {2.0, 4.0}});
  Bytes b;
  r.save(b);
  LookupRoulette back;
  ASSERT_TRUE(back.restore(b));
  EXPECT_EQ(back.probability(kFirstLookup), r.probability(kFirstLookup));
  EXPECT_EQ(back.probability(kLaterLookup), r.probability(kLaterLookup));

  // A state saved with a first-class probability below 1 resumes with it at 1.
  Bytes older;
  older.put(std::array<float, kLookupClasses>{0.25f, 0.5f});
  LookupRoulette resumed;
  ASSERT_TRUE(resumed.restore(older));
  EXPECT_EQ(resumed.probability(kFirstLookup), 1.0f);
  EXPECT_EQ(resumed.probability(kLaterLookup), 0.5f);

  Bytes bad;
  bad.put(std::array<float, kLookupClasses>{0.5f, 0.0f});
  LookupRoulette untouched;
  EXPECT_FALSE(untouched.restore(bad));
  EXPECT_EQ(untouched.probability(kLaterLookup), 1.0f);
  Bytes short_state;
  short_state.put(1.0f);
  EXPECT_FALSE(untouched.restore(short_state));
}

}  // namespace lookup_roulette_test
}  // namespace nimbus::caustics
