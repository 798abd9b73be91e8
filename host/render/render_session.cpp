#include "render/render_session.hpp"

#include <memory>
#include <mutex>

#include "abi/host_services.hpp"
#include "abi/run_state.hpp"
#include "loader/plugin_registry.hpp"
#include "loader/plugin_status.hpp"
#include "render/bind_plugins.hpp"
#include "render/progressive_loop.hpp"
#include "render/render_checkpoint.hpp"
#include "render/render_outputs.hpp"
#include "render/tiling.hpp"
#include "world/world.hpp"

namespace nimbus {
namespace {

RenderFacts facts_of(const RenderJob &job, const BoundPlugins &plugins, RunState &run,
                     const LoopOutcome &loop, double previous_seconds) {
  RenderFacts f;
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
  std::lock_guard lock(run.stats_mutex);
  f.stats = run.stats;
  return f;
}

}  // namespace

Expected<RenderResult> render(const SceneDesc &desc, const RenderOptions &options, PluginRegistry &registry,
                              std::atomic<bool> &cancel, const ProgressFn &progress,
                              const MessageFn &message) {
  const auto resolved = resolve_job(desc, options);
  if (!resolved) return resolved.error();
  const RenderJob &job = resolved.value();
  auto built = World::build(desc, job.filter);
  if (!built) return built.error();
  const World &world = *built.value();
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
  // The sampler builds its tables, the integrator registers its elements; then the film allocates exactly
  // what was requested.
  if (Status s = prepare_plugins(plugins, job, world, run.worker_count); !s) return s.error();
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

  nimbus_render_info_t info{};
  info.header = {sizeof(info), NIMBUS_S_TYPE_RENDER_INFO, nullptr};
  info.worker_count = run.worker_count;
  info.first_iteration = film.iterations() + 1;
  info.planned_iterations = job.stop.iterations;
  if (nimbus_status_t s = plugins.it->begin_render(plugins.integrator.get(), &info); s != NIMBUS_OK)
    return Error{"integrator '" + plugins.integrator.id() +
                 "' failed to begin the render: " + status_text(s)};
  checkpoint.restore_plugin_states(message);

  const LoopOutcome loop = run_progressive_loop(
      job, plugins, run, make_tiles(job.width, job.height, job.region), checkpoint, progress, message);

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
  result.png_path = job.png_path;
  const RenderFacts facts = facts_of(job, plugins, run, loop, checkpoint.previous_seconds());
  if (Status s = write_outputs(job, film, facts); !s) return s.error();
  if (!checkpointed)
    return Error{checkpointed.error().message + " (the image was written to " + result.exr_path + ")"};
  if (loop.failure != NIMBUS_OK)
    return Error{"integrator '" + plugins.integrator.id() + "' failed in " + loop.failure_hook + ": " +
                 status_text(loop.failure) + "; the image so far (" + std::to_string(loop.done) +
                 " iterations) was written to " + result.exr_path};
  return result;
}

}  // namespace nimbus
