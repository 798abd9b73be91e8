// The progressive loop: builds the scene, binds the integrator and light sampler plugins, runs
// iterations until the iteration count, time budget or cancellation, and writes the output files.
// All four ways of stopping end the same way: a complete, valid EXR (and PNG) with the sample count.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/expected.hpp"
#include "scene/scene_desc.hpp"

namespace nimbus {

class PluginRegistry;

struct RenderOptions {
  std::optional<uint64_t> iterations;  // overrides the scene
  std::optional<double> time_seconds;  // overrides the scene
  std::optional<uint64_t> seed;        // overrides the scene
  // Stop once the estimated relMSE of beauty (from odd/even half images, no reference) falls below it.
  std::optional<double> target_error;
  uint32_t threads = 0;               // 0 = all cores
  std::vector<std::string> elements;  // in addition to the scene's
  std::string output_exr;             // PNG preview goes beside it (same stem)
  std::string ocio_config;            // empty = default lookup
  // Empty: nimbus.lights.tree above kTreeLightThreshold lights, nimbus.lights.power otherwise.
  std::string light_sampler;
  // Checkpoints (film/checkpoint.hpp): written between iterations every checkpoint_interval_seconds (<= 0:
  // none on the way) and whenever the loop stops, and kept after the final image so that a finished
  // render can be extended. Empty path: `<output_exr>.ckpt`.
  std::string checkpoint_path;
  double checkpoint_interval_seconds = 300;
  // Continue from the checkpoint instead of starting afresh. `iterations` then counts the total, so a
  // render of 3 resumed with iterations = 6 renders iterations 4 to 6 and equals, bit for bit, a render
  // of 6. A checkpoint already holding that many iterations just rewrites the output files.
  bool resume = false;
};

// Scenes with more lights than this get the many-light tree by default.
inline constexpr uint32_t kTreeLightThreshold = 8;

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
