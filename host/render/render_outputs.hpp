// What a render writes besides the checkpoint: the film set up with exactly the elements asked for
// (LightMix as one "lightmix.<group>" layer per light group), and at the end one multi-layer EXR with the
// render's metadata and the PNG preview beside it.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/expected.hpp"
#include "film/film.hpp"
#include "loader/plugin_registry.hpp"
#include "render/render_job.hpp"

namespace nimbus {

// Film element names of the LightMix groups: "lightmix." + the group name in [a-z0-9_], unique.
std::vector<std::string> lightmix_layer_names(const std::vector<std::string> &groups);

// Requests the job's elements and, with LightMix (which `integrator` must declare as a feature), one layer
// per light group, whose ids go to `lightmix_elements`; then allocates what was requested for `workers`.
Status set_up_film(Film &film, const RenderJob &job, const PluginHandle &integrator,
                   const std::vector<std::string> &light_groups, uint32_t workers,
                   std::vector<int32_t> &lightmix_elements);

// What the EXR's metadata says about the render, besides the job.
struct RenderFacts {
  std::string integrator, light_sampler;  // plugin ids
  std::string guide;                      // the bound guide's id, empty without one
  std::string stopped_by;                 // error, cancel, target_error, iterations or time
  uint64_t iterations = 0;
  double seconds = 0;  // of all the iterations in the image, over every resumed session
  uint32_t threads = 0;
  uint64_t rays = 0;
  std::optional<double> estimated_relmse;  // with an error target
  std::optional<uint64_t> resumed_from;    // when resuming
  std::map<std::string, double> stats;     // what plugins reported
  // Time to first pixel of this render (a resumed one counts from its own start): reading the scene and
  // loading plugins, building the world and preparing the plugins, then the first iteration it rendered
  // (unset when it finished none).
  double load_seconds = 0, setup_seconds = 0;
  std::optional<double> first_iteration_seconds;
  // What `nimbus merge` compares between the tasks of a frame: RenderJob::fingerprint of the bound plugins,
  // and "id@version" of each (the host's version is the EXR's nimbus:version).
  std::string fingerprint, plugin_versions;
};

// job.exr_path with "nimbus:*" metadata, then job.png_path through job.ocio_config. A task of a shared
// frame (job.split) writes a partial EXR instead (film/partial_exr.hpp: the exact sums, nimbus:task,
// nimbus:tasks, nimbus:frame_iterations, nimbus:fingerprint, nimbus:plugins) and no PNG.
Status write_outputs(const RenderJob &job, const Film &film, const RenderFacts &facts);

}  // namespace nimbus
