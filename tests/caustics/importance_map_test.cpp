// The importance map of photon guiding (importance_map.hpp, spec 6.3) against brute force: random marks
// of lookups (positions, radii over six decades, path lengths), merged from several workers, and queries
// at points near and far; I(y) must equal the largest mark whose cell (of the level its radius gives)
// contains y. Also: the cell size is at least 4 r, the importance rule, and the state round trip.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "importance_map.hpp"
#include "state_bytes.hpp"

namespace nimbus::caustics {
namespace importance_map_test {

struct Mark {
  Vec3f p;
  float r, importance;
};

// The brute-force I(y): the cell of each mark's level, by integer cell coordinates.
float brute_force(const CellGrid &grid, const std::vector<Mark> &marks, const Vec3f &y) {
  float best = 0;
  for (const Mark &m : marks) {
    const int level = grid.level_for(m.r);
    // The cell size is a power of two times h0, so 1 / size rounds to the same float either way.
    const double size = std::ldexp(double(grid.h0), level);
    const auto cell_f = [&](float v, float o) { return std::floor(float(v - o) * float(1.0 / size)); };
    if (cell_f(m.p.x, grid.origin.x) == cell_f(y.x, grid.origin.x) &&
        cell_f(m.p.y, grid.origin.y) == cell_f(y.y, grid.origin.y) &&
        cell_f(m.p.z, grid.origin.z) == cell_f(y.z, grid.origin.z))
      best = std::max(best, m.importance);
  }
  return best;
}

TEST(CausticsImportanceMap, MatchesBruteForce) {
  std::mt19937 g(11);
  std::uniform_real_distribution<float> u(-1, 1), unit(0, 1);
  const ImportanceMap proto(Vec3f(0.5f, -2, 3), 10);
  for (int trial = 0; trial < 20; ++trial) {
    ImportanceMap map = proto;
    std::vector<ImportanceMarks> workers(3);
    std::vector<Mark> marks;
    for (int i = 0; i < 400; ++i) {
      // Clusters, so that many queries fall in marked cells; radii log-uniform over 1e-5 .. 10.
      const Vec3f c = Vec3f(0.5f, -2, 3) + Vec3f(u(g), u(g), u(g)) * 5.0f;
      const float r = std::pow(10.0f, -5 + 6 * unit(g));
      const float I = map.importance(std::pow(10.0f, -3 + 5 * unit(g)));
      marks.push_back({c, r, I});
      workers[size_t(i) % 3].add(map.grid(), c, r, I);
    }
    for (ImportanceMarks &w : workers) map.merge(w);
    for (const ImportanceMarks &w : workers) EXPECT_EQ(w.cells().size(), 0u);
    int hits = 0;
    for (int q = 0; q < 2000; ++q) {
      const Mark &m = marks[size_t(q) % marks.size()];
      // Near a mark (within a few radii: inside or next to its cell) or anywhere.
      const Vec3f y = q % 4 == 0 ? Vec3f(0.5f, -2, 3) + Vec3f(u(g), u(g), u(g)) * 5.0f
                                 : m.p + Vec3f(u(g), u(g), u(g)) * (3 * m.r);
      const float want = brute_force(map.grid(), marks, y);
      ASSERT_EQ(map.at(y), want) << "trial " << trial << " query " << q;
      hits += want > 0;
    }
    EXPECT_GT(hits, 500);  // the queries exercise marked cells
  }
}

TEST(CausticsImportanceMap, CellsCoverFourRadiiAndImportanceFallsWithSquaredLength) {
  const ImportanceMap map(Vec3f(0), 100);
  for (float r : {1e-7f, 1e-4f, 0.01f, 1.0f, 50.0f}) {
    const int level = map.grid().level_for(r);
    const float size = std::ldexp(map.grid().h0, level);
    EXPECT_GE(size, 4 * r * (1 - 1e-6f)) << r;
    if (level > 0) {
      EXPECT_LT(size, 8 * r * (1 + 1e-6f)) << r;
    }
  }
  EXPECT_FLOAT_EQ(map.importance(2.0f), 0.25f);
  EXPECT_FLOAT_EQ(map.importance(1e-9f), map.importance(0.1f));  // l_min = 1e-3 R = 0.1
}

TEST(CausticsImportanceMap, StateRoundTripsAndRejectsBadValues) {
  ImportanceMap map(Vec3f(0), 1);
  ImportanceMarks marks;
  for (int i = 0; i < 100; ++i) marks.add(map.grid(), Vec3f(0.01f * float(i), 0, 0), 0.003f, float(i + 1));
  map.merge(marks);
  Bytes b;
  map.save(b);
  ImportanceMap back(Vec3f(0), 1);
  ASSERT_TRUE(back.restore(b));
  EXPECT_EQ(back.cells(), map.cells());
  for (int i = 0; i < 100; ++i) {
    const Vec3f y(0.01f * float(i), 0, 0);
    EXPECT_GE(map.at(y), float(i + 1));  // a cell (>= 4 r = 0.012 wide) may hold two marks
    EXPECT_EQ(back.at(y), map.at(y));
  }

  Bytes bad;
  bad.put(uint64_t(1)), bad.put(uint64_t(1)), bad.put(uint64_t(42)), bad.put(-1.0f);
  ImportanceMap untouched(Vec3f(0), 1);
  EXPECT_FALSE(untouched.restore(bad));
  EXPECT_TRUE(untouched.empty());
  Bytes truncated;
  truncated.put(uint64_t(1)), truncated.put(uint64_t(5));
  EXPECT_FALSE(untouched.restore(truncated));
}

}  // namespace importance_map_test
}  // namespace nimbus::caustics
