// AliasTable: the pmf it reports is the rate at which it really picks, for every 24-bit uniform number
// the renderer's random floats can take - including bins far below the floats' resolution (lights 1e9
// apart in power), where an unrounded threshold would be met ~60x too often for its weight.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include <nimbus/cpp/alias_table.hpp>

namespace nimbus {
namespace alias_table_test {

// Picks per bin over all 2^24 values u = m / 2^24: exact frequencies, no noise.
std::vector<uint64_t> count_all_u(const AliasTable &table) {
  std::vector<uint64_t> counts(table.size(), 0);
  for (uint32_t m = 0; m < (1u << 24); ++m) ++counts[size_t(table.sample(float(m) * 0x1p-24f))];
  return counts;
}

void expect_pmf_is_rate(const std::vector<double> &weights, double rel_tol) {
  const AliasTable table(weights);
  const std::vector<uint64_t> counts = count_all_u(table);
  double sum = 0;
  for (double w : weights) sum += w;
  for (size_t i = 0; i < weights.size(); ++i) {
    const double rate = double(counts[i]) * 0x1p-24;
    EXPECT_NEAR(rate, table.pmf(i), rel_tol * table.pmf(i) + 1e-12)
        << "bin " << i << " of " << weights.size();
    if (weights[i] == 0) {
      EXPECT_EQ(counts[i], 0u) << "a zero weight is never picked";
    }
    // Weights well above the resolution (2^-24 per value of u) keep their proportion.
    if (weights[i] / sum > 1e-4) {
      EXPECT_NEAR(table.pmf(i), weights[i] / sum, 2e-3 * weights[i] / sum);
    }
  }
}

TEST(AliasTable, TwoBinsNineDecadesApart) { expect_pmf_is_rate({1.0, 1e-9}, 1e-6); }

TEST(AliasTable, PowerOfTwoBinCountWithTinyWeights) {
  std::vector<double> w(1024, 1.0);
  w[3] = 1e-12, w[700] = 0, w[1000] = 1e-7;
  expect_pmf_is_rate(w, 1e-3);
}

TEST(AliasTable, OddBinCount) {
  std::vector<double> w;
  for (int i = 0; i < 999; ++i) w.push_back(i % 3 == 0 ? 1e-9 : double(i % 17 + 1));
  expect_pmf_is_rate(w, 2e-3);
}

TEST(AliasTable, AllZeroIsEmpty) {
  const AliasTable table(std::vector<double>{0, 0});
  float pmf = 1;
  EXPECT_EQ(table.sample(0.5f, &pmf), -1);
  EXPECT_EQ(pmf, 0.0f);
}

}  // namespace alias_table_test
}  // namespace nimbus
