// The render job: a parsed scene and the command line's options resolved once into what one render does
// (image, seed, threads, stopping rules, film elements, the plugins to bind, outputs, checkpoints and the
// checkpoint's fingerprint). Everything after resolve_job() reads the job, never RenderOptions, so each
// precedence between the scene and the command line is decided here and only here.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nimbus/cpp/task_split.hpp>

#include "core/expected.hpp"
#include "scene/scene_desc.hpp"

namespace nimbus {

// What the command line adds to or overrides in the scene.
struct RenderOptions {
  std::optional<uint64_t> iterations;  // overrides the scene
  std::optional<double> time_seconds;  // overrides the scene
  std::optional<uint64_t> seed;        // overrides the scene
  // Stop once the estimated relMSE of beauty (from odd/even half images, no reference) falls below it.
  std::optional<double> target_error;
  std::optional<std::string> integrator;  // overrides the scene
  std::optional<FilterType> filter;       // overrides the scene
  uint32_t threads = 0;                   // 0 = all cores
  std::vector<std::string> elements;      // in addition to the scene's
  std::string output_exr;                 // PNG preview goes beside it (same stem)
  std::string ocio_config;                // empty = default lookup
  // Empty: nimbus.lights.tree above kTreeLightThreshold lights, nimbus.lights.power otherwise.
  std::string light_sampler;
  // A guiding plugin id, "none", or empty: the scene's, else the integrator's default (RenderJob::guide_for).
  std::string guide;
  // Checkpoints (film/checkpoint.hpp): written between iterations every checkpoint_interval_seconds (<= 0:
  // none on the way) and whenever the loop stops, and kept after the final image so that a finished
  // render can be extended. Empty path: `<output_exr>.ckpt`.
  std::string checkpoint_path;
  double checkpoint_interval_seconds = 300;
  // Continue from the checkpoint instead of starting afresh. `iterations` then counts the total, so a
  // render of 3 resumed with iterations = 6 renders iterations 4 to 6 and equals, bit for bit, a render
  // of 6. A checkpoint already holding that many iterations just rewrites the output files.
  bool resume = false;
  double load_seconds =
      0;  // what reading the scene and loading plugins took the caller (time to first pixel)
  // This render's share of the frame (--task K --tasks N): the frame-wide iterations K + 1 + k N, written
  // as a partial EXR for `nimbus merge`. `iterations` stays the frame's total.
  uint32_t task = 0, tasks = 1;
};

// Scenes with more lights than this get the many-light tree by default.
inline constexpr uint32_t kTreeLightThreshold = 8;
// Iterations when neither the scene nor the command line gives any stopping rule.
inline constexpr uint64_t kDefaultIterations = 64;

// The loop stops at the first rule reached; 0 means no such rule.
struct StopRules {
  uint64_t iterations = 0;
  double time_seconds = 0;
  double target_error = 0;
};

struct RenderJob {
  const SceneDesc *scene = nullptr;  // the parsed scene; outlives the job
  uint32_t width = 0, height = 0;
  uint32_t region[4] = {0, 0, 0, 0};  // as RenderDesc::region: all zero = the whole image
  uint64_t seed = 1;
  uint32_t threads = 0;  // 0 = all cores
  uint32_t max_depth = 0;
  FilterType filter = FilterType::Box;
  StopRules stop;        // stop.iterations counts this task's iterations (the frame's for a whole render)
  sdk::TaskSplit split;  // which of the frame's iterations this render has (task_split.hpp)
  uint64_t frame_iterations = 0;  // the frame's total when stopping by iterations, else 0

  std::string integrator;  // a plugin id or short name ("pt")
  // The integrator's options as the scene and command line set them (checked once it is bound).
  std::vector<RenderDesc::OptionSetting> integrator_options;
  std::string light_sampler;  // a plugin id; empty: chosen by light count (light_sampler_for)
  std::string guide;          // a plugin id, "none", or empty: the integrator's default (guide_for)
  std::string guide_where;  // where the job names it, for errors ("scene.yaml:12:3: render.guide", "--guide")
  // Film elements besides beauty, in the order requested (scene first), without "lightmix", which asks
  // for one layer per light group instead.
  std::vector<std::string> elements;
  bool lightmix = false;

  std::string exr_path, png_path;  // the PNG preview beside the EXR
  std::string ocio_config;         // the display transform's config for the PNG
  std::string checkpoint_path;
  double checkpoint_interval_seconds = 300;
  bool resume = false;
  double load_seconds = 0;  // RenderOptions::load_seconds

  // The light sampler to bind for a world of `light_count` lights.
  std::string light_sampler_for(uint32_t light_count) const;
  // The guide to bind for an integrator whose descriptor lists `features`: the job's, else the one the
  // integrator names by the feature "default-guide=ID"; empty for none ("none" asks for none).
  std::string guide_for(const std::vector<std::string> &features) const;
  // Whether the job itself names the guide (then a missing plugin is an error, not a notice).
  bool guide_named() const { return !guide.empty() && guide != "none"; }

  // What the film's sums depend on, one "key=value" per line; a checkpoint resumes only into a render
  // with the same lines (read_checkpoint names those that differ). The scene's text and every file the
  // parser read for it are hashed (SceneDesc::sources), so any edit to them counts; the other lines catch
  // what the command line can change without editing a file. The ids are those of the bound plugins.
  // `options`: the integrator's options as resolved against its declarations. `guide_id`: the bound
  // guide's, empty without one (then the fingerprint has no guide line).
  // The lines are those of the frame: every task of one frame has the same (`nimbus merge` compares them).
  std::string fingerprint(const std::string &integrator_id, const std::string &light_sampler_id,
                          const std::vector<std::pair<std::string, std::string>> &options,
                          const std::string &guide_id = {}) const;
  // A task's checkpoint resumes only the same task: its fingerprint has this line besides (empty for a
  // whole render, whose checkpoints predate tasks).
  std::string task_line() const;
};

// Resolves and checks the job; `scene` must outlive it. Errors name what is inconsistent.
Expected<RenderJob> resolve_job(const SceneDesc &scene, const RenderOptions &options);

}  // namespace nimbus
