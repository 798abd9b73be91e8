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

#include "abi/hook_watch.hpp"
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
  // The iteration being rendered, set before its tiles start: its frame-wide number (what plugins see), and
  // its number within this render, which counts 1, 2, ... also in a task of a shared frame
  // (RenderJob::split).
  uint64_t iteration = 0, task_iteration = 0;
  uint64_t seed = 1;  // of the random streams the rng service derives
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

  // The tile each worker is rendering (empty between tiles): the film service drops, and counts, writes
  // outside it, which would race with the worker that owns those pixels.
  struct alignas(sdk::kCacheLineBytes) WorkerTile {
    nimbus_tile_t tile{};
  };
  std::vector<WorkerTile> worker_tiles;
  std::atomic<uint64_t> outside_tile_writes{0};
  bool in_tile(const nimbus_thread_ctx_t *tc, uint32_t x, uint32_t y) const {
    if (!tc || tc->worker_index >= worker_tiles.size()) return false;
    const nimbus_tile_t &t = worker_tiles[tc->worker_index].tile;
    return x >= t.x0 && x < t.x1 && y >= t.y0 && y < t.y1;
  }

  HookWatch hooks;
  // Which tiles of the current iteration have started (their sums saved in the undo copy), so that a
  // failed or rescued iteration can be undone.
  std::unique_ptr<std::atomic<uint8_t>[]> tile_started;

  // Service lookups the host could not answer, as "id@revision", for the message when a plugin then fails.
  std::mutex missing_services_mutex;
  std::vector<std::string> missing_services;

  // Statistics plugins add through the progress service (written into the EXR metadata).
  std::mutex stats_mutex;
  std::map<std::string, double> stats;
  // The phase a plugin reports (shown by the progress display).
  std::mutex phase_mutex;
  std::string phase;
  uint64_t phase_done = 0, phase_total = 0;
};

}  // namespace nimbus
