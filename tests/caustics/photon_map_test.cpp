// Photon map (solver spec 10 iii): kd-tree radius queries return exactly the brute-force sets (inclusive
// d^2 <= r^2 computed the same way) for empty, tiny and large maps and for uniform, clustered, coplanar,
// collinear and duplicate points, radii from 0 to beyond the scene, with and without the occupancy
// filter in front (radii below, at and above its reach, far from the origin); the filter turns most empty
// lookups away; the tree does not depend on how many threads build it. Also: octahedral direction
// encoding and the lookup-radius histogram.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <thread>
#include <vector>

#include "photon_map.hpp"

namespace nimbus::caustics {
namespace photon_map_test {

enum class Layout { Uniform, Clustered, Coplanar, Collinear, Duplicates };

std::vector<Photon> make_photons(size_t n, Layout layout, std::mt19937_64 &g) {
  std::uniform_real_distribution<float> u(-1, 1);
  std::normal_distribution<float> gauss(0, 0.01f);
  std::vector<Vec3f> centres;
  for (int c = 0; c < 5; ++c) centres.push_back({u(g), u(g), u(g)});
  std::vector<Photon> ph(n);
  for (size_t i = 0; i < n; ++i) {
    Vec3f p;
    switch (layout) {
      case Layout::Uniform:
        p = {u(g), u(g), u(g)};
        break;
      case Layout::Clustered:
        p = centres[i % centres.size()] + Vec3f(gauss(g), gauss(g), gauss(g));
        break;
      case Layout::Coplanar:
        p = {u(g), u(g), 0.25f};
        break;
      case Layout::Collinear:
        p = {u(g), 0.5f, -0.5f};
        break;
      case Layout::Duplicates:
        p = centres[i % 3];
        break;
    }
    p.store(ph[i].p);
    ph[i].bits = uint32_t(i);  // identity for comparing sets
  }
  return ph;
}

std::vector<uint32_t> brute_force(const std::vector<Photon> &ph, const Vec3f &q, float r) {
  std::vector<uint32_t> out;
  const float r2 = r * r;
  for (const Photon &p : ph) {
    const float dx = p.p[0] - q.x, dy = p.p[1] - q.y, dz = p.p[2] - q.z;
    if (dx * dx + dy * dy + dz * dz <= r2) out.push_back(p.bits);
  }
  std::sort(out.begin(), out.end());
  return out;
}

float random_radius(std::mt19937_64 &g) {
  const int kind = std::uniform_int_distribution<int>(0, 9)(g);
  if (kind == 0) return 0.0f;
  if (kind == 1) return 5.0f;  // beyond the scene
  return std::exp(std::uniform_real_distribution<float>(std::log(1e-4f), std::log(1.0f))(g));
}

TEST(CausticsPhotonMap, RadiusQueriesEqualBruteForce) {
  std::mt19937_64 g(42);
  std::uniform_real_distribution<float> u(-1.2f, 1.2f);
  for (size_t n : {size_t(0), size_t(1), size_t(7), size_t(8), size_t(9), size_t(1000), size_t(100000)}) {
    for (Layout layout :
         {Layout::Uniform, Layout::Clustered, Layout::Coplanar, Layout::Collinear, Layout::Duplicates}) {
      const std::vector<Photon> original = make_photons(n, layout, g);
      std::vector<Photon> ph = original;
      PhotonKdTree tree;
      tree.build(ph);
      ASSERT_EQ(tree.size(), n);
      const int queries = n >= 100000 ? 60 : 300;
      for (int i = 0; i < queries; ++i) {
        // Query near stored points half of the time (exact hits and radius-boundary cases).
        Vec3f q(u(g), u(g), u(g));
        if (n > 0 && i % 2 == 0) q = original[std::uniform_int_distribution<size_t>(0, n - 1)(g)].position();
        float r = random_radius(g);
        if (n > 0 && i % 7 == 0) {  // a radius exactly at some photon's distance
          const Photon &o = original[std::uniform_int_distribution<size_t>(0, n - 1)(g)];
          const float dx = o.p[0] - q.x, dy = o.p[1] - q.y, dz = o.p[2] - q.z;
          r = std::sqrt(dx * dx + dy * dy + dz * dz);
        }
        std::vector<uint32_t> got;
        tree.query(q, r, [&](const PhotonData &p, float d2) {
          EXPECT_LE(d2, r * r);
          got.push_back(p.bits);
        });
        std::sort(got.begin(), got.end());
        ASSERT_EQ(got, brute_force(original, q, r)) << "n " << n << " layout " << int(layout) << " r " << r;
      }
    }
  }
}

// With the occupancy filter: the same sets as brute force for radii below, at and just above its reach
// (which skip it), at the origin and 10^4 away from it, in every layout.
TEST(CausticsPhotonMap, FilteredQueriesEqualBruteForce) {
  std::mt19937_64 g(7);
  for (float offset : {0.0f, 1e4f}) {
    // 20,000: above OccupancyFilter::kParallelPhotons, marked in two halves.
    for (size_t n : {size_t(1), size_t(9), size_t(5000), size_t(20000)}) {
      for (Layout layout :
           {Layout::Uniform, Layout::Clustered, Layout::Coplanar, Layout::Collinear, Layout::Duplicates}) {
        std::vector<Photon> original = make_photons(n, layout, g);
        for (Photon &p : original) (p.position() + Vec3f(offset)).store(p.p);
        for (float reach : {1e-3f, 0.05f, 0.7f}) {
          std::vector<Photon> ph = original;
          PhotonKdTree tree;
          tree.build(ph, serial_for, reach);
          ASSERT_EQ(tree.filter_reach(), reach);
          std::uniform_real_distribution<float> u(-1.2f, 1.2f), share(0, 1);
          for (int i = 0; i < 400; ++i) {
            Vec3f q = Vec3f(u(g), u(g), u(g)) + Vec3f(offset);
            const Photon &o = original[std::uniform_int_distribution<size_t>(0, n - 1)(g)];
            // Near a photon: at a random distance up to twice the reach, in a random direction.
            if (i % 2 == 0)
              q = o.position() + normalize(Vec3f(u(g), u(g), u(g)) + Vec3f(1e-3f)) * (2 * reach * share(g));
            float r = reach * share(g);
            if (i % 5 == 0) r = reach;
            if (i % 5 == 1) r = std::nextafter(reach, kInfinity);  // beyond the reach: no filter
            if (i % 7 == 0) {  // exactly some photon's distance (when within the reach)
              const float dx = o.p[0] - q.x, dy = o.p[1] - q.y, dz = o.p[2] - q.z;
              r = std::min(reach, std::sqrt(dx * dx + dy * dy + dz * dz));
            }
            std::vector<uint32_t> got;
            tree.query(q, r, [&](const PhotonData &p, float) { got.push_back(p.bits); });
            std::sort(got.begin(), got.end());
            ASSERT_EQ(got, brute_force(original, q, r)) << "n " << n << " layout " << int(layout) << " reach "
                                                        << reach << " r " << r << " offset " << offset;
          }
        }
      }
    }
  }
}

// The filter answers "nothing here" for most lookups that find nothing: photons on two small patches of a
// plane, lookups all over the plane (inside the map's bounds) with radii up to the reach.
TEST(CausticsPhotonMap, FilterTurnsEmptyLookupsAway) {
  std::mt19937_64 g(11);
  std::uniform_real_distribution<float> u(-1, 1);
  std::vector<Photon> ph(4000);
  for (size_t i = 0; i < ph.size(); ++i) {
    const Vec3f c = i % 2 ? Vec3f(-0.8f, -0.8f, 0) : Vec3f(0.8f, 0.8f, 0);
    (c + Vec3f(u(g), u(g), 0) * 0.05f).store(ph[i].p);
  }
  const float reach = 0.004f;
  OccupancyFilter filter;
  filter.build(ph.size(), reach, [&](size_t i) { return ph[i].position(); });
  int empty = 0, turned_away = 0;
  for (int i = 0; i < 5000; ++i) {
    const Vec3f q(u(g), u(g), 0);
    const float r = reach * std::uniform_real_distribution<float>(0.5f, 1)(g);
    bool found = false;
    for (const Photon &p : ph) found = found || length_squared(p.position() - q) <= r * r;
    if (found) {
      EXPECT_TRUE(filter.may_hold(q, r));
      continue;
    }
    ++empty;
    turned_away += filter.may_hold(q, r) ? 0 : 1;
  }
  ASSERT_GT(empty, 4500);
  EXPECT_GT(turned_away, 0.95 * empty) << turned_away << " of " << empty;
  // No filter: without a reach, or for radii above it.
  EXPECT_TRUE(filter.may_hold(Vec3f(0.1f, -0.3f, 0), 2 * reach));
  OccupancyFilter none;
  none.build(ph.size(), 0, [&](size_t i) { return ph[i].position(); });
  EXPECT_TRUE(none.may_hold(Vec3f(0.1f, -0.3f, 0), reach));
  EXPECT_EQ(none.bytes(), 0u);
}

// The radius histogram's quantile: at least the asked share of radii lie at or below it, and it is within
// 25 % of the exact quantile (four bins per octave); it does not depend on the order radii were added in.
TEST(CausticsPhotonMap, RadiusHistogramQuantile) {
  std::mt19937_64 g(13);
  std::vector<float> radii(100000);
  for (float &r : radii)
    r = std::exp(std::uniform_real_distribution<float>(std::log(1e-5f), std::log(10.0f))(g));
  RadiusHistogram a, b, c;
  for (size_t i = 0; i < radii.size(); ++i) (i % 2 ? a : b).add(radii[i]);
  c.add(b), c.add(a);
  RadiusHistogram all;
  for (size_t i = radii.size(); i-- > 0;) all.add(radii[i]);
  std::vector<float> sorted = radii;
  std::sort(sorted.begin(), sorted.end());
  for (double q : {0.5, 0.9, 0.95, 1.0}) {
    const float got = all.quantile(q);
    EXPECT_EQ(got, c.quantile(q));
    const size_t below = size_t(std::upper_bound(sorted.begin(), sorted.end(), got) - sorted.begin());
    EXPECT_GE(double(below), q * double(sorted.size())) << q;
    const float exact = sorted[std::min(sorted.size() - 1, size_t(q * double(sorted.size())))];
    EXPECT_LE(got, exact * 1.25f * 1.0001f) << q;
  }
  RadiusHistogram empty;
  empty.add(0.0f), empty.add(-1.0f), empty.add(kInfinity);
  EXPECT_EQ(empty.quantile(0.95), 0.0f);
}

// The tree (photon order) and the occupancy filter are the same whether they are built by one or many
// threads.
TEST(CausticsPhotonMap, TreeIndependentOfThreads) {
  std::mt19937_64 g(3);
  const std::vector<Photon> original = make_photons(50000, Layout::Clustered, g);
  static_assert(50000 >= OccupancyFilter::kParallelPhotons, "the filter's parallel path");
  const float reach = 0.002f;
  PhotonKdTree ta, tb;
  ta.build(original, serial_for, reach);
  const ParallelFor threads = [](size_t count, const std::function<void(size_t)> &fn) {
    std::vector<std::thread> pool;
    for (unsigned t = 0; t < 8; ++t)
      pool.emplace_back([&, t] {
        for (size_t i = count - 1 - t; i < count; i -= 8) fn(i);  // reverse, interleaved order
      });
    for (auto &th : pool) th.join();
  };
  tb.build(original, threads, reach);
  ASSERT_EQ(ta.size(), tb.size());
  ASSERT_EQ(ta.bytes(), tb.bytes());
  for (size_t i = 0; i < ta.size(); ++i) ASSERT_EQ(ta.data()[i].bits, tb.data()[i].bits) << i;
  // The same filter bits: the same answer everywhere, near photons and away from them.
  std::uniform_real_distribution<float> u(-1.2f, 1.2f), share(0, 1);
  size_t held = 0;
  for (int i = 0; i < 100000; ++i) {
    Vec3f q(u(g), u(g), u(g));
    if (i % 2 == 0) q = original[size_t(i) % original.size()].position() + Vec3f(u(g), u(g), u(g)) * 0.01f;
    const float r = reach * share(g);
    const bool a = ta.may_hold(q, r);
    ASSERT_EQ(a, tb.may_hold(q, r)) << i;
    held += a;
  }
  EXPECT_GT(held, 1000u);
  EXPECT_LT(held, 99000u);
}

TEST(CausticsPhotonMap, OctahedralDirections) {
  std::mt19937_64 g(5);
  std::normal_distribution<float> n(0, 1);
  for (int i = 0; i < 100000; ++i) {
    Vec3f v(n(g), n(g), n(g));
    if (i < 6) v = Vec3f(0, 0, 0), v[i % 3] = (i < 3 ? 1.0f : -1.0f);
    v = normalize(v);
    const Vec3f d = decode_octahedral(encode_octahedral(v));
    EXPECT_LT(length(d - v), 1e-4f) << v.x << " " << v.y << " " << v.z;
  }
}

}  // namespace photon_map_test
}  // namespace nimbus::caustics
