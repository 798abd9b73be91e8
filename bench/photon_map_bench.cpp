// Photon-map lookups as the "pool" scene makes them: caustics on a pool floor seen by camera lookups,
// which are cheap but many and mostly find 0 or 1 photon. Photons lie on the floor z = 0 (x, y in
// [0,10]): half uniform, half within +-0.01 of 40 sine-like caustic curves. 400,000 fixed lookups of
// radius 0.025 (x U[0.7,1.3]): 60 % on the floor, 40 % on the wall x = 0 (y in [0,10], z in [0,3]),
// which holds photons only near its bottom edge. BM_PhotonMapQuery prints ns per lookup with the
// occupancy filter (reach = 95th percentile of the radii) and without, in random order and in scanline
// order (neighbouring lookups after each other, as a tile's pixels make them); BM_PhotonMapBuild the
// build (one thread). Compare two builds of the map by running both binaries alternately.
//
//   build/bin/nimbus_photon_map_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "photon_map.hpp"

namespace nimbus::caustics {
namespace {

constexpr uint32_t kSeed = 20240611;
constexpr size_t kQueries = 400000;
constexpr float kRadius = 0.025f;

struct Query {
  Vec3f q;
  float r;
};

std::vector<Photon> make_photons(size_t n) {
  std::mt19937 rng(kSeed);
  std::uniform_real_distribution<float> u01(0, 1), u10(0, 10), jitter(-0.01f, 0.01f), phase(0, 6.2831853f);
  std::uniform_int_distribution<int> curve(0, 39);
  float c[40], phi[40];
  for (int k = 0; k < 40; ++k) c[k] = 0.3f + 9.4f * float(k) / 39, phi[k] = phase(rng);
  std::vector<Photon> photons(n);
  for (Photon &ph : photons) {
    float x = u10(rng), y;
    if (u01(rng) < 0.5f) {
      y = u10(rng);
    } else {
      const int k = curve(rng);
      y = c[k] + 0.3f * std::sin(2 * x + phi[k]) + jitter(rng);
    }
    ph = Photon{
        {uint32_t(rng()), encode_octahedral(Vec3f(0, 0, 1)), {1, 1, 1}, 1, 1, 1}, {x, y, 0}, 0, 0, 0, 0};
  }
  return photons;
}

// Another seed than the photons', so the two streams are independent. `coherent`: the same lookups in
// scanline order of 0.2 m rows, as a tile of neighbouring pixels makes them; otherwise in random order.
const std::vector<Query> &queries(bool coherent) {
  static const std::vector<Query> random_order = [] {
    std::mt19937 rng(kSeed + 1);
    std::uniform_real_distribution<float> u01(0, 1), u10(0, 10), u3(0, 3), f(0.7f, 1.3f);
    std::vector<Query> v(kQueries);
    for (Query &q : v) {
      const bool floor = u01(rng) < 0.6f;
      const float a = u10(rng), b = floor ? u10(rng) : u3(rng);
      q = Query{floor ? Vec3f(a, b, 0) : Vec3f(0, a, b), kRadius * f(rng)};
    }
    return v;
  }();
  static const std::vector<Query> scanline = [] {
    std::vector<Query> v = random_order;
    const auto key = [](const Query &q) {
      const bool wall = q.q.x == 0;
      const float a = wall ? q.q.y : q.q.x, b = wall ? q.q.z : q.q.y;
      return std::make_tuple(wall, int(b / 0.2f), a);
    };
    std::sort(v.begin(), v.end(), [&](const Query &x, const Query &y) { return key(x) < key(y); });
    return v;
  }();
  return coherent ? scanline : random_order;
}

float reach_p95() {
  std::vector<float> r;
  for (const Query &q : queries(false)) r.push_back(q.r);
  const size_t k = size_t(0.95 * double(r.size() - 1));
  std::nth_element(r.begin(), r.begin() + k, r.end());
  return r[k];
}

void BM_PhotonMapQuery(benchmark::State &state, size_t n, bool filter, bool coherent) {
  std::vector<Photon> photons = make_photons(n);
  const float reach = filter ? reach_p95() : 0;
  PhotonKdTree tree;
  const auto t0 = std::chrono::steady_clock::now();
  tree.build(photons, serial_for, reach);
  const double build_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  const std::vector<Query> &qs = queries(coherent);
  size_t found = 0;
  for (auto _ : state) {
    for (const Query &q : qs) {
      float sum = 0;
      uint32_t count = 0;
      tree.query(q.q, q.r, [&](const PhotonData &, float d2) { sum += d2, ++count; });
      benchmark::DoNotOptimize(sum);
      found += count;
    }
  }
  const double lookups = double(state.iterations()) * double(qs.size());
  state.SetItemsProcessed(int64_t(lookups));
  state.counters["per_query"] =
      benchmark::Counter(lookups, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["photons_per_query"] = double(found) / lookups;
  state.counters["build_ms"] = build_ms;
  state.counters["reach"] = tree.filter_reach();
  state.counters["map_MiB"] = double(tree.bytes()) / (1 << 20);
}

void BM_PhotonMapBuild(benchmark::State &state, size_t n, bool filter) {
  const std::vector<Photon> source = make_photons(n);
  const float reach = filter ? reach_p95() : 0;
  double ms = 0;
  for (auto _ : state) {
    state.PauseTiming();
    std::vector<Photon> photons = source;
    state.ResumeTiming();
    const auto t0 = std::chrono::steady_clock::now();
    PhotonKdTree tree;
    tree.build(photons, serial_for, reach);
    benchmark::DoNotOptimize(tree.size());
    ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  }
  state.counters["build_ms"] = ms / double(state.iterations());
}

const int kRegistered = [] {
  for (const size_t n : {size_t(42000), size_t(200000)})
    for (const bool filter : {true, false}) {
      const std::string suffix = "/" + std::to_string(n) + (filter ? "/filter" : "/nofilter");
      for (const bool coherent : {false, true})
        benchmark::RegisterBenchmark(
            ("BM_PhotonMapQuery" + suffix + (coherent ? "/scanline" : "/random")).c_str(), BM_PhotonMapQuery,
            n, filter, coherent)
            ->Unit(benchmark::kMillisecond);
      benchmark::RegisterBenchmark(("BM_PhotonMapBuild" + suffix).c_str(), BM_PhotonMapBuild, n, filter)
          ->Unit(benchmark::kMillisecond);
    }
  return 0;
}();

}  // namespace
}  // namespace nimbus::caustics

BENCHMARK_MAIN();
