#include "render/bind_plugins.hpp"

#include <vector>

#include "loader/plugin_interface.hpp"
#include "loader/plugin_options.hpp"
#include "loader/plugin_status.hpp"

namespace nimbus {

Expected<BoundPlugins> bind_plugins(PluginRegistry &registry, const RenderJob &job, uint32_t light_count,
                                    const nimbus_host_t *host) {
  BoundPlugins p;
  auto integrator = registry.instantiate(job.integrator, NIMBUS_KIND_INTEGRATOR, host);
  if (!integrator) return Error{job.scene->path + ": integrator: " + integrator.error().message};
  p.integrator = std::move(integrator).value();
  auto sampler = registry.instantiate(job.light_sampler_for(light_count), NIMBUS_KIND_LIGHT_SAMPLER, host);
  if (!sampler) return Error{"light sampler: " + sampler.error().message};
  p.sampler = std::move(sampler).value();
  auto it = interface_of<nimbus_integrator_v1_t>(p.integrator, NIMBUS_IFACE_INTEGRATOR, kIntegratorSize10);
  if (!it) return it.error();
  auto ls =
      interface_of<nimbus_light_sampler_v1_t>(p.sampler, NIMBUS_IFACE_LIGHT_SAMPLER, kLightSamplerMinSize);
  if (!ls) return ls.error();
  p.it = it.value();
  p.ls = ls.value();
  std::vector<OptionRequest> requests;
  for (const auto &o : job.integrator_options) requests.push_back({o.name, o.value, o.where, o.hint});
  auto options = resolve_options(p.integrator.id(), p.integrator.record().options, requests);
  if (!options) return options.error();
  p.options = std::move(options.value());
  return p;
}

Status prepare_plugins(const BoundPlugins &p, const RenderJob &job, const World &world,
                       uint32_t worker_count) {
  nimbus_scene_info_t scene_info{};
  scene_info.header = {sizeof(scene_info), NIMBUS_S_TYPE_SCENE_INFO, nullptr};
  scene_info.light_count = world.lights.count();
  scene_info.worker_count = worker_count;
  world.geometry->sphere_center().store(scene_info.scene_center);
  scene_info.scene_radius = world.geometry->sphere_radius();
  if (nimbus_status_t s = p.ls->prepare(p.sampler.get(), &scene_info); s != NIMBUS_OK)
    return Error{"light sampler '" + p.sampler.id() + "' failed to prepare: " + status_text(s)};

  std::vector<nimbus_option_t> opts;
  for (const auto &[k, v] : p.options) opts.push_back({k.c_str(), v.c_str()});
  nimbus_render_setup_t setup{};
  setup.header = {sizeof(setup), NIMBUS_S_TYPE_RENDER_SETUP, nullptr};
  setup.width = job.width;
  setup.height = job.height;
  setup.max_depth = job.max_depth;
  setup.option_count = uint32_t(opts.size());
  setup.seed = job.seed;
  setup.options = opts.data();
  setup.light_sampler = p.sampler.get();
  setup.light_sampler_iface = p.ls;
  if (nimbus_status_t s = p.it->prepare(p.integrator.get(), &setup); s != NIMBUS_OK)
    return Error{"integrator '" + p.integrator.id() + "' failed to prepare: " + status_text(s)};
  return Ok{};
}

}  // namespace nimbus
