#include "render/progressive_loop.hpp"

#include <algorithm>
#include <atomic>
#include <mutex>

#include <tbb/parallel_for.h>

#include "core/denormals.hpp"

namespace nimbus {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Every tile of iteration i, in parallel in the run's arena; the first failing status, or NIMBUS_OK. Each
// tile's sums are saved before it starts; once a rescue has begun no tile starts.
nimbus_status_t render_tiles(const BoundPlugins &p, RunState &run, const Tiling &tiling, IterationUndo &undo,
                             uint64_t i) {
  std::atomic<nimbus_status_t> tile_status{NIMBUS_OK};
  for (size_t t = 0; t < tiling.tiles.size(); ++t) run.tile_started[t].store(0, std::memory_order_relaxed);
  run.arena->execute([&] {
    tbb::parallel_for(size_t(0), tiling.tiles.size(), [&](size_t t) {
      const FlushDenormals float_mode;
      const int wi = tbb::this_task_arena::current_thread_index();
      nimbus_thread_ctx_t tc{
          sizeof(nimbus_thread_ctx_t), uint32_t(wi < 0 ? 0 : wi), run.worker_count, 0, nullptr, 0};
      nimbus_tile_t tile = tiling.tiles[t];
      tile.iteration = i;
      // Saved, then marked started, then the rescue flag read: a rescue that sees the tile unstarted
      // reads its sums, one that sees it started reads the saved copy (sequentially consistent order).
      if (run.hooks.rescuing()) return;
      undo.save(run.film, tile);
      run.tile_started[t].store(1);
      if (run.hooks.rescuing()) return;
      run.worker_tiles[tc.worker_index].tile = tile;
      const nimbus_status_t s = p.it->render_tile(p.integrator.get(), &tc, &tile);
      run.worker_tiles[tc.worker_index].tile = {};
      if (s != NIMBUS_OK) {
        nimbus_status_t expected = NIMBUS_OK;
        tile_status.compare_exchange_strong(expected, s);
      }
    });
  });
  return tile_status.load();
}

// After a tile failed: the started tiles get their saved sums back and the iteration's splats are
// dropped, so the film holds the iterations before it, exactly.
void undo_iteration(RunState &run, const Tiling &tiling, const IterationUndo &undo) {
  for (size_t t = 0; t < tiling.tiles.size(); ++t)
    if (run.tile_started[t].load()) undo.restore(run.film, tiling.tiles[t]);
  run.film.discard_splats();
}

}  // namespace

std::string LoopOutcome::stopped_by(const StopRules &stop) const {
  return failure != NIMBUS_OK                           ? "error"
         : cancelled                                    ? "cancel"
         : reached_target                               ? "target_error"
         : (stop.iterations && done >= stop.iterations) ? "iterations"
                                                        : "time";
}

LoopOutcome run_progressive_loop(const RenderJob &job, const BoundPlugins &p, RunState &run,
                                 const Tiling &tiling, IterationUndo &undo, RenderCheckpoint &checkpoint,
                                 const ProgressFn &progress, const MessageFn &message) {
  const StopRules &stop = job.stop;
  Film &film = run.film;
  std::atomic<bool> &cancel = *run.cancel;
  LoopOutcome out;
  out.resumed_from = out.done = film.iterations();
  const auto t0 = Clock::now();
  checkpoint.start(out.done, t0);
  while (!cancel.load() && !out.reached_target) {
    const uint64_t done = out.done;
    if (stop.iterations && done >= stop.iterations) break;
    if (stop.time_seconds > 0 && done > out.resumed_from) {
      // Stop when another iteration would overrun the budget (estimated from this run's mean since it started
      // or resumed).
      const double elapsed = seconds_since(t0);
      if (elapsed + elapsed / double(done - out.resumed_from) > stop.time_seconds) break;
    }
    // Between iterations the sums are complete (splats merged): the only safe moment to save them.
    checkpoint.save_if_due(film, done, message);
    // The tasks of a shared frame take turns through its iterations (RenderJob::split); the film counts this
    // render's own.
    const uint64_t local = done + 1, i = job.split.frame_number(local);
    run.iteration = i, run.task_iteration = local;
    const std::string &id = p.integrator.id();
    nimbus_status_t s = NIMBUS_OK;
    {
      HookScope hook(run.hooks, id, "begin_iteration");
      s = p.it->begin_iteration(p.integrator.get(), i);
    }
    if (s != NIMBUS_OK) {
      out.failure = s, out.failure_hook = "begin_iteration";
      break;
    }
    {
      HookScope hook(run.hooks, id, "render_tile");
      s = render_tiles(p, run, tiling, undo, i);
    }
    if (s != NIMBUS_OK) {
      undo_iteration(run, tiling, undo);
      out.failure = s, out.failure_hook = "render_tile";
      break;
    }
    film.merge_splats();
    // Optional: a sampler's table may end before end_iteration (kLightSamplerMinSize).
    if (NIMBUS_HAS_MEMBER(p.ls, nimbus_light_sampler_v1_t, end_iteration) && p.ls->end_iteration) {
      HookScope hook(run.hooks, p.sampler.id(), "end_iteration");
      p.ls->end_iteration(p.sampler.get(), i);
    }
    {
      HookScope hook(run.hooks, id, "end_iteration");
      s = p.it->end_iteration(p.integrator.get(), i);
    }
    // The iteration's samples are all in: they count even when its end_iteration fails.
    film.end_iteration();
    out.done = local;
    if (local == out.resumed_from + 1) out.first_iteration_seconds = seconds_since(t0);
    if (s != NIMBUS_OK) {
      out.failure = s, out.failure_hook = "end_iteration";
      break;
    }
    if (run.error_estimate) {
      run.error_estimate->end_iteration(local);
      if (local % 2 == 0) {
        out.estimated_error = run.error_estimate->relmse(film);
        if (out.estimated_error < stop.target_error) out.reached_target = true;
      }
    }
    if (progress) {
      RenderProgress r;
      r.iteration = out.done;
      r.total_iterations = stop.iterations;
      r.elapsed_seconds = seconds_since(t0);
      r.time_budget = stop.time_seconds;
      r.samples_per_second =
          double(tiling.pixels) * (out.done - out.resumed_from) / std::max(r.elapsed_seconds, 1e-9);
      std::lock_guard lock(run.phase_mutex);
      r.phase = run.phase;
      progress(r);
    }
  }
  out.seconds = seconds_since(t0);
  out.cancelled = cancel.load();
  // The last checkpoint, while the plugins still hold the state of the last iteration. After a plugin
  // failure the sums hold a partial iteration, so the last periodic checkpoint is kept instead.
  if (out.failure == NIMBUS_OK) out.checkpointed = checkpoint.save_if_behind(film, out.done);
  HookScope hook(run.hooks, p.integrator.id(), "end_render");
  p.it->end_render(p.integrator.get(),
                   out.failure != NIMBUS_OK ? out.failure : (out.cancelled ? NIMBUS_E_CANCELLED : NIMBUS_OK));
  return out;
}

}  // namespace nimbus
