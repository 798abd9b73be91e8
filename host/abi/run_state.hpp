// What changes while a render runs: the film and error estimate the film service writes, the iteration
// being rendered, the worker arena, ray counters, and what plugins report (log lines, statistics, the
// phase). The render session makes it and drives the loop; the host services (abi/) read and write it.
// The world the render reads is apart (world/world.hpp) and never changes.
#pragma once

#include <atomic>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <tbb/task_arena.h>

#include <nimbus/nimbus.hpp>

#include "film/error_estimate.hpp"
#include "film/film.hpp"

namespace nimbus {

using LogFn = std::function<void(int level, const std::string &plugin_id, const std::string &msg)>;

struct RunState {
  // A width x height film, and an arena of `threads` workers (0 = all cores).
  RunState(uint32_t width, uint32_t height, uint32_t threads, uint64_t seed);
  RunState(const RunState &) = delete;
  RunState &operator=(const RunState &) = delete;

  Film film;
  // Only with a target error: odd-iteration beauty, for the reference-free error estimate.
  std::unique_ptr<ErrorEstimate> error_estimate;
  uint64_t iteration = 0;  // the iteration being rendered (1-based), set before its tiles start
  uint64_t seed = 1;       // of the random streams the rng service derives
  // Film element of each LightMix group (empty when LightMix was not requested).
  std::vector<int32_t> lightmix_elements;

  std::unique_ptr<tbb::task_arena> arena;
  uint32_t worker_count = 1;
  std::thread::id main_thread;
  std::atomic<bool> *cancel = nullptr;  // set by Ctrl-C or the time budget; owned by the caller
  LogFn log;

  // Rays traced, per worker (a cache line each, so counting costs no contention); summed after the render.
  struct alignas(sdk::kCacheLineBytes) RayCounter {
    uint64_t rays = 0;
  };
  std::vector<RayCounter> ray_counters;
  uint64_t rays_traced() const {
    uint64_t n = 0;
    for (const RayCounter &c : ray_counters) n += c.rays;
    return n;
  }

  // Statistics plugins add through the progress service (written into the EXR metadata).
  std::mutex stats_mutex;
  std::map<std::string, double> stats;
  // The phase a plugin reports (shown by the progress display).
  std::mutex phase_mutex;
  std::string phase;
  uint64_t phase_done = 0, phase_total = 0;
};

}  // namespace nimbus
