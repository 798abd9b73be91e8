#include "render/render_session.hpp"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <mutex>

#include <unistd.h>

#include "abi/host_services.hpp"
#include "abi/run_state.hpp"
#include "core/denormals.hpp"
#include "loader/plugin_registry.hpp"
#include "loader/plugin_status.hpp"
#include "render/bind_plugins.hpp"
#include "render/progressive_loop.hpp"
#include "render/render_checkpoint.hpp"
#include "render/render_outputs.hpp"
#include "render/tiling.hpp"
#include "render/watchdog.hpp"
#include "world/world.hpp"

namespace nimbus {
namespace {

RenderFacts facts_of(const RenderJob &job, const BoundPlugins &plugins, RunState &run,
                     const LoopOutcome &loop, double previous_seconds, double setup_seconds) {
  RenderFacts f;
  f.load_seconds = job.load_seconds;
  f.setup_seconds = setup_seconds;
  if (loop.done > loop.resumed_from) f.first_iteration_seconds = loop.first_iteration_seconds;
  f.integrator = plugins.integrator.id();
  f.light_sampler = plugins.sampler.id();
  f.guide = plugins.guide.id();
  f.stopped_by = loop.stopped_by(job.stop);
  f.iterations = loop.done;
  f.seconds = previous_seconds + loop.seconds;
  f.threads = run.worker_count;
  f.rays = run.rays_traced();
  if (run.error_estimate) f.estimated_relmse = loop.estimated_error;
  if (job.resume) f.resumed_from = loop.resumed_from;
  f.fingerprint = job.fingerprint(f.integrator, f.light_sampler, plugins.options, f.guide);
  for (const PluginHandle *p : {&plugins.integrator, &plugins.sampler, &plugins.guide}) {
    if (p->id().empty()) continue;
    const nimbus_version_t &v = p->record().version;
    f.plugin_versions += (f.plugin_versions.empty() ? "" : ",") + p->id() + "@" + std::to_string(v.major) +
                         "." + std::to_string(v.minor) + "." + std::to_string(v.patch);
  }
  std::lock_guard lock(run.stats_mutex);
  f.stats = run.stats;
  return f;
}

// A failing plugin's message, with the services it asked for and this host lacks (usually the cause).
Error with_missing_services(RunState &run, Error e) {
  std::lock_guard lock(run.missing_services_mutex);
  if (run.missing_services.empty()) return e;
  e.message += "; it asked for service";
  e.message += run.missing_services.size() > 1 ? "s " : " ";
  for (size_t i = 0; i < run.missing_services.size(); ++i)
    e.message += (i ? ", " : "") + run.missing_services[i];
  e.message += ", which this host does not provide";
  return e;
}

// The image could not be written where asked (a full disk, a directory gone read-only): rather than lose
// the render, it goes to the temporary directory, and the error says where.
Error write_elsewhere(const RenderJob &job, const Film &film, const RenderFacts &facts, Error e) {
  RenderJob there = job;
  const std::string stem = std::filesystem::path(job.exr_path).stem().string();
  const auto dir = std::filesystem::temp_directory_path();
  there.exr_path = (dir / (stem + "-" + std::to_string(::getpid()) + ".exr")).string();
  there.png_path = (dir / (stem + "-" + std::to_string(::getpid()) + ".png")).string();
  if (write_outputs(there, film, facts))
    e.message += "; the image was written to " + there.exr_path + " and " + there.png_path + " instead";
  return e;
}

// What a render whose plugin hook hangs past the time budget leaves: the iterations complete when the
// hook was entered (a render_tile's started tiles come from the undo copy; an end_iteration's samples are
// all in), written as a normal image, then the process ends, since the hook's thread cannot be stopped.
struct Rescue {
  const RenderJob *job = nullptr;
  const BoundPlugins *plugins = nullptr;
  RunState *run = nullptr;
  std::atomic<const IterationUndo *> undo{nullptr};
  std::atomic<const Tiling *> tiling{nullptr};
  const MessageFn *message = nullptr;

  [[noreturn]] void operator()(const HookWatch::Site &site, double seconds_in_hook) {
    run->hooks.start_rescue();
    const IterationUndo *u = undo.load();
    const Tiling *t = tiling.load();
    std::unique_ptr<Film> image = run->film.snapshot();
    if (site.hook == "render_tile" && u && t)
      for (size_t i = 0; i < t->tiles.size(); ++i)
        if (run->tile_started[i].load()) u->restore(*image, t->tiles[i]);
    if (site.hook == "end_iteration") image->set_iterations(image->iterations() + 1);
    char head[320];
    std::snprintf(head, sizeof head, "plugin '%s' has been in %s for %.0f s, past the time budget of %g s: ",
                  site.plugin.c_str(), site.hook.c_str(), seconds_in_hook, job->stop.time_seconds);
    std::string text = head;
    if (u && image->iterations() > 0) {
      LoopOutcome loop;
      loop.done = image->iterations();
      loop.failure = NIMBUS_E_INTERNAL;
      RenderFacts facts = facts_of(*job, *plugins, *run, loop, 0, 0);
      const Status written = write_outputs(*job, *image, facts);
      text += written ? "the image of its " + std::to_string(loop.done) +
                            " complete iterations was written to " + job->exr_path
                      : "the image could not be written: " + written.error().message;
    } else {
      text += "no iteration had completed, so no image was written";
    }
    if (*message) (*message)(NIMBUS_LOG_ERROR, text);
    std::fflush(stderr);
    std::_Exit(1);
  }
};

}  // namespace

Expected<RenderResult> render(const SceneDesc &desc, const RenderOptions &options, PluginRegistry &registry,
                              std::atomic<bool> &cancel, const ProgressFn &progress,
                              const MessageFn &message) {
  const auto started = std::chrono::steady_clock::now();
  const auto resolved = resolve_job(desc, options);
  if (!resolved) return resolved.error();
  const RenderJob &job = resolved.value();
  auto built = World::build(desc, job.filter);
  if (!built) return built.error();
  const World &world = *built.value();
  // The main thread runs plugin hooks and the arena's callers like the workers: all flush denormals.
  const FlushDenormals float_mode;
  RunState run(job.width, job.height, job.threads, job.seed);
  run.cancel = &cancel;
  run.log = [&](int level, const std::string &id, const std::string &msg) {
    if (message) message(level, id.empty() ? msg : id + ": " + msg);
  };
  HostServices services(&world, &run);

  auto bound = bind_plugins(registry, job, world.lights.count(), services.host());
  if (!bound) return bound.error();
  const BoundPlugins &plugins = bound.value();
  if (!plugins.notice.empty() && message) message(NIMBUS_LOG_WARNING, plugins.notice);
  Rescue rescue;
  rescue.job = &job, rescue.plugins = &plugins, rescue.run = &run, rescue.message = &message;
  const Watchdog watchdog(run.hooks, job.stop.time_seconds,
                          [&](const HookWatch::Site &site, double seconds) { rescue(site, seconds); });
  // The sampler builds its tables, the integrator registers its elements; then the film allocates exactly
  // what was requested.
  if (Status s = prepare_plugins(plugins, job, world, run.worker_count, run.hooks); !s)
    return with_missing_services(run, s.error());
  Film &film = run.film;
  if (Status s = set_up_film(film, job, plugins.integrator, world.lights.group_names(), run.worker_count,
                             run.lightmix_elements);
      !s)
    return s.error();

  // Restore the sums before the first iteration, or warn before replacing someone's work.
  RenderCheckpoint checkpoint(job, plugins.integrator.id(), plugins.sampler.id(), plugins.guide.id(),
                              plugins.options);
  const PluginStates states(plugins);
  checkpoint.keep_plugin_states(&states);
  if (Status s = checkpoint.restore_or_warn(film, message); !s) return s.error();
  if (job.stop.target_error > 0)
    run.error_estimate = std::make_unique<ErrorEstimate>(job.width, job.height, run.worker_count);
  IterationUndo undo(film);
  const Tiling tiling = make_tiles(job.width, job.height, job.region);
  run.tile_started = std::make_unique<std::atomic<uint8_t>[]>(tiling.tiles.size());

  nimbus_render_info_t info{};
  info.header = {sizeof(info), NIMBUS_S_TYPE_RENDER_INFO, nullptr};
  info.worker_count = run.worker_count;
  info.first_iteration = job.split.frame_number(film.iterations() + 1);
  info.planned_iterations = job.stop.iterations;
  info.task_index = job.split.index;
  info.task_count = job.split.count;
  nimbus_status_t begun = NIMBUS_OK;
  {
    HookScope hook(run.hooks, plugins.integrator.id(), "begin_render");
    begun = plugins.it->begin_render(plugins.integrator.get(), &info);
  }
  if (begun != NIMBUS_OK)
    return with_missing_services(run, Error{"integrator '" + plugins.integrator.id() +
                                            "' failed in begin_render: " + status_text(begun)});
  checkpoint.restore_plugin_states(message);
  rescue.undo.store(&undo);
  rescue.tiling.store(&tiling);

  const double setup_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  const LoopOutcome loop =
      run_progressive_loop(job, plugins, run, tiling, undo, checkpoint, progress, message);

  // Write what we have, whatever ended the loop. The loop saved the checkpoint first, so that an image
  // write that fails still leaves a way to recover the render.
  const Status &checkpointed = loop.checkpointed;
  RenderResult result;
  result.iterations = loop.done;
  result.seconds = loop.seconds;
  result.cancelled = loop.cancelled;
  result.nonfinite_samples = film.nonfinite_count();
  result.rays = run.rays_traced();
  result.resumed_from = job.resume ? loop.resumed_from : 0;
  result.checkpoint_path = checkpoint.saved_path();
  result.exr_path = job.exr_path;
  result.png_path = job.split.whole() ? job.png_path : std::string();
  const RenderFacts facts = facts_of(job, plugins, run, loop, checkpoint.previous_seconds(), setup_seconds);
  if (Status s = write_outputs(job, film, facts); !s) return write_elsewhere(job, film, facts, s.error());
  if (!checkpointed)
    return Error{checkpointed.error().message + " (the image was written to " + result.exr_path + ")"};
  const std::string so_far = "; the image of its " + std::to_string(loop.done) +
                             " complete iterations was written to " + result.exr_path;
  if (loop.failure != NIMBUS_OK)
    return with_missing_services(run, Error{"integrator '" + plugins.integrator.id() + "' failed in " +
                                            loop.failure_hook + ": " + status_text(loop.failure) + so_far});
  // Samples the film refused: the render went on, but the pixels that lost them are darker by their
  // share, so the image is not what the scene renders to.
  if (const uint64_t n = run.outside_tile_writes.load())
    return Error{"integrator '" + plugins.integrator.id() + "' wrote " + std::to_string(n) +
                 " samples outside its tile in render_tile; they were dropped (they would race with the "
                 "tile's own thread)" +
                 so_far};
  if (result.nonfinite_samples)
    return Error{"integrator '" + plugins.integrator.id() + "' gave the film " +
                 std::to_string(result.nonfinite_samples) +
                 " NaN or infinite samples in render_tile; they were dropped" + so_far};
  return result;
}

}  // namespace nimbus
