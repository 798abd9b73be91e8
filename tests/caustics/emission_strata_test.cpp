// Stratified emission samples (emission_strata.hpp): the Hilbert map is a bijection whose consecutive
// cells touch; the samples of a pass of 4^k paths put exactly one point in each cell of the 2^k x 2^k
// grid; a path with a uniformly chosen index gets a uniform point (chi-square, passes of awkward sizes);
// and a task's run of consecutive paths stays within a small part of the square.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>
#include <vector>

#include "chi_square.hpp"
#include "emission_strata.hpp"
#include "photon_pass.hpp"

namespace nimbus::caustics {
namespace emission_strata_test {

using test::Pcg32;

float uniform(Pcg32 &rng) { return rng.uniform(); }

TEST(CausticsEmissionStrata, HilbertCurveIsABijectionOfTouchingCells) {
  for (uint32_t order : {1u, 2u, 5u, 8u}) {
    const uint64_t cells = uint64_t(1) << (2 * order);
    std::set<std::pair<uint32_t, uint32_t>> seen;
    uint32_t px = 0, py = 0;
    for (uint64_t d = 0; d < cells; ++d) {
      uint32_t x = 0, y = 0;
      hilbert_cell(d, order, x, y);
      ASSERT_LT(x, 1u << order);
      ASSERT_LT(y, 1u << order);
      ASSERT_TRUE(seen.insert({x, y}).second) << "order " << order << " d " << d;
      if (d > 0) {
        ASSERT_EQ(std::abs(int(x) - int(px)) + std::abs(int(y) - int(py)), 1) << "order " << order;
      }
      px = x, py = y;
    }
    EXPECT_EQ(seen.size(), cells);
  }
}

// The textbook inverse (rotation by branches), which the masked one must match cell for cell: the
// emission samples, and so every caustic render, stay what they were.
void classic_hilbert_cell(uint64_t d, uint32_t order, uint32_t &x, uint32_t &y) {
  x = y = 0;
  for (uint32_t s = 1; s < (uint32_t(1) << order); s <<= 1) {
    const uint32_t rx = 1 & uint32_t(d >> 1), ry = 1 & uint32_t(d ^ rx);
    if (ry == 0) {
      if (rx == 1) x = s - 1 - x, y = s - 1 - y;
      std::swap(x, y);
    }
    x += s * rx, y += s * ry;
    d >>= 2;
  }
}

TEST(CausticsEmissionStrata, HilbertCellMatchesTheTextbookInverse) {
  Pcg32 rng(5);
  for (uint32_t order = 1; order <= kHilbertOrder; ++order) {
    const uint64_t cells = uint64_t(1) << (2 * order);
    // Every cell of the small grids; 2^16 random ones and the last of the large.
    const uint64_t checks = std::min<uint64_t>(cells, 1u << 16);
    for (uint64_t k = 0; k < checks; ++k) {
      uint64_t d = k;
      if (cells > checks) {
        const uint64_t high = rng.next();
        d = k + 1 == checks ? cells - 1 : (high << 32 | rng.next()) % cells;
      }
      uint32_t x = 0, y = 0, cx = 0, cy = 0;
      hilbert_cell(d, order, x, y);
      classic_hilbert_cell(d, order, cx, cy);
      ASSERT_EQ(x, cx) << "order " << order << " d " << d;
      ASSERT_EQ(y, cy) << "order " << order << " d " << d;
    }
  }
}

TEST(CausticsEmissionStrata, PassOfFourToTheKPathsFillsEveryCellOnce) {
  Pcg32 rng(17);
  for (uint32_t k : {1u, 3u, 5u}) {
    const uint32_t side = 1u << k;
    const uint64_t n = uint64_t(side) * side;
    std::vector<int> count(n, 0);
    for (uint64_t p = 0; p < n; ++p) {
      const Vec2f s = emission_sample(p, n, uniform(rng), uniform(rng), uniform(rng));
      ASSERT_GE(s.x, 0.0f);
      ASSERT_LT(s.x, 1.0f);
      ASSERT_GE(s.y, 0.0f);
      ASSERT_LT(s.y, 1.0f);
      ++count[size_t(uint32_t(s.y * float(side)) * side + uint32_t(s.x * float(side)))];
    }
    for (uint64_t c = 0; c < n; ++c) ASSERT_EQ(count[c], 1) << "k " << k << " cell " << c;
  }
}

// The marginal of one path: p uniform in [0, n), then the sample. Over a 32 x 32 grid, for pass sizes
// that are not powers of two (one path, a prime, a task and a half).
TEST(CausticsEmissionStrata, RandomPathGetsAUniformPoint) {
  constexpr int kSide = 32, kSamples = 400000;
  for (uint64_t n : {uint64_t(1), uint64_t(7), uint64_t(1536), uint64_t(100003)}) {
    Pcg32 rng(uint64_t(23) + n);
    std::vector<int> count(kSide * kSide, 0);
    for (int i = 0; i < kSamples; ++i) {
      const uint64_t p = std::min<uint64_t>(n - 1, uint64_t(uniform(rng) * double(n)));
      const Vec2f s = emission_sample(p, n, uniform(rng), uniform(rng), uniform(rng));
      ++count[size_t(int(s.y * kSide) * kSide + int(s.x * kSide))];
    }
    const double expected = double(kSamples) / (kSide * kSide);
    double chi2 = 0;
    for (const int c : count) chi2 += (c - expected) * (c - expected) / expected;
    EXPECT_GT(test::chi_square_survival(chi2, kSide * kSide - 1), 0.01) << "n " << n << ": chi2 " << chi2;
  }
}

// 1,024 consecutive paths of a pass of 65,536 cover 1/64 of the curve: their points lie in a box of at
// most a few times sqrt(1/64) on a side, where independent points would span the whole square.
TEST(CausticsEmissionStrata, ConsecutivePathsStayTogether) {
  Pcg32 rng(29);
  constexpr uint64_t kPass = 65536, kTask = 1024;
  for (uint64_t begin = 0; begin < kPass; begin += 7 * kTask) {
    float lo[2] = {1, 1}, hi[2] = {0, 0};
    for (uint64_t p = begin; p < begin + kTask; ++p) {
      const Vec2f s = emission_sample(p, kPass, uniform(rng), uniform(rng), uniform(rng));
      lo[0] = std::min(lo[0], s.x), hi[0] = std::max(hi[0], s.x);
      lo[1] = std::min(lo[1], s.y), hi[1] = std::max(hi[1], s.y);
    }
    EXPECT_LE((hi[0] - lo[0]) * (hi[1] - lo[1]), 4.0f / 64) << "task at " << begin;
  }
}

}  // namespace emission_strata_test
}  // namespace nimbus::caustics

namespace nimbus::caustics {
namespace emission_strata_test {

// A task cut short by its memory guard leaves out the last paths of its order: task_path() must order
// the run as a permutation, rotated differently from pass to pass, so that over many passes every path
// (and its emission stratum) is left out about equally often, not one fixed stratum every time.
TEST(CausticsPhotonPass, TaskOrderRotatesFromPassToPass) {
  const uint64_t b = 2048, e = 3072, n = e - b;
  std::vector<int> cut(n, 0);
  const int passes = 4096;
  for (uint32_t pass = 1; pass <= uint32_t(passes); ++pass) {
    std::vector<bool> seen(n, false);
    for (uint64_t i = 0; i < n; ++i) {
      const uint64_t p = task_path(pass, b, e, i);
      ASSERT_GE(p, b);
      ASSERT_LT(p, e);
      ASSERT_FALSE(seen[p - b]) << "not a permutation";
      seen[p - b] = true;
      if (i >= n - n / 4) ++cut[p - b];  // the last quarter: what a guard at 3/4 leaves out
    }
  }
  // Each path is cut with probability 1/4 per pass: 1024 +- 28 (1 sigma) over 4096 passes; 6 sigma.
  for (uint64_t k = 0; k < n; ++k) EXPECT_NEAR(cut[k], passes / 4, 170) << "path " << b + k;
}

}  // namespace emission_strata_test
}  // namespace nimbus::caustics
