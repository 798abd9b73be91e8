// The plugins of one render: the integrator the job names and the light sampler it chooses, created
// for the render's host, their interface tables checked against the SDK 1.0 sizes, then prepared for
// the world. Ids and features come from the loader's validated descriptor copies (PluginHandle).
#pragma once

#include <nimbus/nimbus.h>

#include "abi/hook_watch.hpp"
#include "core/expected.hpp"
#include "loader/plugin_registry.hpp"
#include "render/render_job.hpp"
#include "world/world.hpp"

namespace nimbus {

struct BoundPlugins {
  // Destroyed in reverse order: the guide and the sampler before the integrator that was handed them.
  PluginHandle integrator, sampler, guide;  // guide: empty handle when none is bound
  const nimbus_integrator_v1_t *it = nullptr;
  const nimbus_light_sampler_v1_t *ls = nullptr;
  const nimbus_guiding_v1_t *guide_v1 = nullptr;  // the guide's rev 1 table, if it has one
  const nimbus_guiding_v2_t *guide_v2 = nullptr;  // the guide's rev 2 table, if it has one
  // Set when the integrator's default guide is not installed: the render goes on without one.
  std::string notice;
  // Every option the integrator declares, with the job's value or the default (plugin_options.hpp).
  std::vector<std::pair<std::string, std::string>> options;
};

// Creates the plugins for `host` (which must outlive them); the sampler is chosen for `light_count`, the
// guide as RenderJob::guide_for says. The job's integrator options are checked against the integrator's
// declarations. A guide the job names must load and serve "nimbus.iface.guiding" rev 2 or rev 1; the
// integrator's default guide, when not installed, is left out with a notice.
Expected<BoundPlugins> bind_plugins(PluginRegistry &registry, const RenderJob &job, uint32_t light_count,
                                    const nimbus_host_t *host);

// prepare() of all: the sampler builds its tables for the world, the guide learns the scene's size, then
// the integrator receives its setup (resolution, options, seed, the sampler and the guide) and registers
// the film elements it can produce. Each call runs inside a HookScope of `hooks` (for the watchdog).
Status prepare_plugins(const BoundPlugins &plugins, const RenderJob &job, const World &world,
                       uint32_t worker_count, HookWatch &hooks);

}  // namespace nimbus
