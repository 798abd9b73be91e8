// Path tracer throughput on the default scene against Embree's own closest-hit throughput on the same
// geometry. Prints samples/s and rays/s of `nimbus.pt` (all threads), and rays/s of a batch of
// rtcIntersect1 calls with the same thread count, for diffuse-bounce-like rays inside the scene; and
// Embree's rate for the same kind of rays one, four or eight per call on a scene of triangles.
//
//   build/bin/nimbus_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <embree3/rtcore.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <filesystem>
#include <random>

#include <nimbus/cpp/sampling.hpp>
#include "abi/host_services.hpp"
#include "abi/run_state.hpp"
#include "core/hash.hpp"
#include "film/iteration_undo.hpp"
#include "loader/plugin_registry.hpp"
#include "render/render_session.hpp"
#include "render/tiling.hpp"
#include "scene/scene_parser.hpp"
#include "world/world.hpp"

namespace nimbus {
namespace {

const std::string kScene = std::string(NIMBUS_SOURCE_DIR) + "/scenes/default.yaml";
constexpr uint64_t kIterations = 4;

std::string plugin_dir() {
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  return (exe.parent_path().parent_path() / "lib/nimbus/plugins").string();
}

void BM_PathTracerDefaultScene(benchmark::State &state) {
  auto desc = parse_scene_file(kScene);
  if (!desc) return state.SkipWithError(desc.error().message.c_str());
  desc->render.integrator = "pt";  // the scene names none: the default would be the caustics solver
  PluginRegistry registry([](int, const std::string &) {});
  HostServices discovery(nullptr);
  registry.discover({plugin_dir()}, discovery.host());
  const std::string out = (std::filesystem::temp_directory_path() / "nimbus_bench.exr").string();
  uint64_t samples = 0, rays = 0;
  double seconds = 0;
  for (auto _ : state) {
    RenderOptions opt;
    opt.iterations = kIterations;
    opt.output_exr = out;
    std::atomic<bool> cancel{false};
    auto r = render(desc.value(), opt, registry, cancel, {}, {});
    if (!r) return state.SkipWithError(r.error().message.c_str());
    samples += uint64_t(desc->render.width) * desc->render.height * r->iterations;
    rays += r->rays;
    seconds += r->seconds;
    state.SetIterationTime(r->seconds);  // the render loop only, not scene build or file output
  }
  state.counters["samples_per_s"] = double(samples) / seconds;
  state.counters["rays_per_s"] = double(rays) / seconds;
  state.counters["rays_per_sample"] = double(rays) / double(samples);
}
BENCHMARK(BM_PathTracerDefaultScene)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(3);

// A scene's geometry, and rays from random points inside its bounds in uniformly distributed
// directions: the mix of ray lengths and directions a diffuse path tracer traces, without any shading.
struct RayBatch {
  std::unique_ptr<World> world;
  std::vector<RTCRayHit> rays;
  static Expected<RayBatch> of(const std::string &scene_file, size_t n) {
    auto desc = parse_scene_file(scene_file);
    if (!desc) return desc.error();
    auto world = World::build(desc.value(), desc->render.filter);
    if (!world) return world.error();
    RayBatch b{std::move(*world), std::vector<RTCRayHit>(n)};
    const Vec3f lo = b.world->geometry->bounds_min(), hi = b.world->geometry->bounds_max();
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> U(0, 1);
    for (RTCRayHit &rh : b.rays) {
      const Vec3f o =
          lo + (hi - lo) * Vec3f(0.05f + 0.9f * U(rng), 0.05f + 0.9f * U(rng), 0.05f + 0.9f * U(rng));
      const Vec3f d = sample_uniform_sphere(U(rng), U(rng));
      rh.ray = {o.x, o.y, o.z, 0, d.x, d.y, d.z, 0, kInfinity, 0xFFFFFFFFu, 0, 0};
    }
    return b;
  }
};

// Rays rays[0..N) (N the packet's width) traced as one packet by `intersect` (rtcIntersect4 or 8);
// returns how many hit something.
template <class Packet, class Intersect>
uint64_t intersect_packet(RTCScene scene, RTCIntersectContext &ic, const RTCRayHit *rays,
                          Intersect intersect) {
  constexpr int N = sizeof(Packet::ray.tnear) / sizeof(float);
  alignas(32) int valid[N];
  Packet p;
  for (int k = 0; k < N; ++k) {
    const RTCRay &r = rays[k].ray;
    valid[k] = -1;
    p.ray.org_x[k] = r.org_x, p.ray.org_y[k] = r.org_y, p.ray.org_z[k] = r.org_z, p.ray.tnear[k] = r.tnear;
    p.ray.dir_x[k] = r.dir_x, p.ray.dir_y[k] = r.dir_y, p.ray.dir_z[k] = r.dir_z, p.ray.time[k] = r.time;
    p.ray.tfar[k] = r.tfar, p.ray.mask[k] = r.mask, p.ray.id[k] = 0, p.ray.flags[k] = 0;
    p.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
  }
  intersect(valid, scene, &ic, &p);
  uint64_t hits = 0;
  for (int k = 0; k < N; ++k) hits += p.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID;
  return hits;
}

// Closest hits of the batch on all cores, `width` rays per Embree call: 1 (rtcIntersect1, as the
// renderer traces) or 4 or 8 (rtcIntersect4 / 8 on consecutive, unrelated rays: one path per lane).
void closest_hits(benchmark::State &state, const std::string &scene_file, size_t width) {
  constexpr size_t kRays = 1 << 20;
  auto batch = RayBatch::of(scene_file, kRays);
  if (!batch) return state.SkipWithError(batch.error().message.c_str());
  RTCScene scene = batch->world->geometry->rtc_scene();
  RunState run(1, 1, 0, 1);  // all cores, as nimbus.pt
  uint64_t hits = 0;
  for (auto _ : state) {
    std::atomic<uint64_t> h{0};
    run.arena->execute([&] {
      tbb::parallel_for(tbb::blocked_range<size_t>(0, kRays, 4096), [&](const tbb::blocked_range<size_t> &r) {
        RTCIntersectContext ic;
        rtcInitIntersectContext(&ic);
        uint64_t local = 0;
        for (size_t i = r.begin(); i + width <= r.end(); i += width) {
          if (width == 1) {
            RTCRayHit rh = batch->rays[i];
            rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
            rtcIntersect1(scene, &ic, &rh);
            local += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
          } else {
            local += width == 4 ? intersect_packet<RTCRayHit4>(scene, ic, &batch->rays[i], rtcIntersect4)
                                : intersect_packet<RTCRayHit8>(scene, ic, &batch->rays[i], rtcIntersect8);
          }
        }
        h += local;
      });
    });
    hits += h.load();
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(kRays));
  state.counters["rays_per_s"] =
      benchmark::Counter(double(state.iterations()) * kRays, benchmark::Counter::kIsRate);
  state.counters["hit_fraction"] = double(hits) / (double(state.iterations()) * kRays);
}

// Embree's own closest-hit rate on the default scene, for rays one at a time.
void BM_EmbreeClosestHitDefaultScene(benchmark::State &state) { closest_hits(state, kScene, 1); }
BENCHMARK(BM_EmbreeClosestHitDefaultScene)->Unit(benchmark::kMillisecond)->UseRealTime();

// The same on a scene of triangles only (the host's analytic shapes answer one ray at a time), by rays
// per call: what tracing unrelated paths in packets would gain or lose in Embree.
void BM_EmbreeClosestHitPacketsInterior(benchmark::State &state) {
  closest_hits(state, std::string(NIMBUS_SOURCE_DIR) + "/scenes/caustics/interior.yaml",
               size_t(state.range(0)));
}
BENCHMARK(BM_EmbreeClosestHitPacketsInterior)
    ->Arg(1)
    ->Arg(4)
    ->Arg(8)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// What the iteration undo (film/iteration_undo.hpp) costs an iteration: every tile's sums copied before it
// is rendered, on the default scene's film (beauty only), on the same thread count as the render. Compare
// the time per iteration with BM_PathTracerDefaultScene's.
void BM_IterationUndoDefaultScene(benchmark::State &state) {
  auto desc = parse_scene_file(kScene);
  if (!desc) return state.SkipWithError(desc.error().message.c_str());
  Film film(desc->render.width, desc->render.height);
  const Tiling tiling = make_tiles(desc->render.width, desc->render.height, desc->render.region);
  IterationUndo undo(film);
  for (auto _ : state)
    tbb::parallel_for(size_t(0), tiling.tiles.size(), [&](size_t t) { undo.save(film, tiling.tiles[t]); });
  state.counters["bytes_per_iteration"] = double(undo.bytes());
}
BENCHMARK(BM_IterationUndoDefaultScene)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace nimbus

BENCHMARK_MAIN();
