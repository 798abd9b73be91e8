// A render session: the scene and the command line resolved into a render job (render_job.hpp), the world
// built, the integrator and light sampler bound (bind_plugins.hpp), the film set up and restored from a
// checkpoint when resuming, the progressive loop run (progressive_loop.hpp) until the iteration count,
// time budget, error target or cancellation, and the output files written (render_outputs.hpp). All four
// ways of stopping end the same way: a complete, valid EXR (and PNG) with the sample count.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>

#include "core/expected.hpp"
#include "render/render_job.hpp"
#include "scene/scene_desc.hpp"

namespace nimbus {

class PluginRegistry;

struct RenderProgress {
  uint64_t iteration = 0;         // completed iterations
  uint64_t total_iterations = 0;  // 0 when stopping by time only
  double elapsed_seconds = 0;
  double time_budget = 0;         // 0 = none
  double samples_per_second = 0;  // camera samples (pixels x iterations) per second
  std::string phase;              // what a plugin reports it is doing, if anything
};

struct RenderResult {
  uint64_t iterations = 0;
  double seconds = 0;
  bool cancelled = false;
  uint64_t nonfinite_samples = 0;
  uint64_t rays = 0;          // closest-hit and shadow rays traced
  uint64_t resumed_from = 0;  // iterations the checkpoint held when resuming, else 0
  std::string exr_path, png_path;
  std::string checkpoint_path;  // empty when no checkpoint was written
};

using ProgressFn = std::function<void(const RenderProgress &)>;
// level: NIMBUS_LOG_*; the line is complete (plugin id included).
using MessageFn = std::function<void(int level, const std::string &line)>;

// Renders `desc`. `cancel` is polled between iterations (and by plugins); when it becomes true the
// current iteration finishes and the files are written. Errors name what failed; if the render
// started, the film is written before an error is returned.
// Warnings (e.g. an existing checkpoint about to be replaced) go to `message`.
Expected<RenderResult> render(const SceneDesc &desc, const RenderOptions &options, PluginRegistry &registry,
                              std::atomic<bool> &cancel, const ProgressFn &progress,
                              const MessageFn &message);

}  // namespace nimbus
