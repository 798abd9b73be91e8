#include "render/bind_plugins.hpp"

#include <vector>

#include "loader/plugin_interface.hpp"
#include "loader/plugin_options.hpp"
#include "loader/plugin_status.hpp"

namespace nimbus {
namespace {

// Binds the guide the job asks for (RenderJob::guide_for). A guide serves rev 2 (photon paths in primary
// sample space, SDK 1.5) or rev 1; the integrator fetches whichever it drives.
Status bind_guide(PluginRegistry &registry, const RenderJob &job, const nimbus_host_t *host,
                  BoundPlugins &p) {
  const std::string id = job.guide_for(p.integrator.record().features);
  if (id.empty()) return Ok{};
  auto guide = registry.instantiate(id, NIMBUS_KIND_GUIDING, host);
  if (!guide) {
    if (job.guide_named())
      return Error{(job.guide_where.empty() ? job.scene->path + ": guide" : job.guide_where) + ": " +
                   guide.error().message};
    p.notice =
        "integrator '" + p.integrator.id() + "' renders without its default guide: " + guide.error().message;
    return Ok{};
  }
  const nimbus_plugin_t *g = guide.value().get();
  const auto *v2 = static_cast<const nimbus_guiding_v2_t *>(g->get_interface(g, NIMBUS_IFACE_GUIDING, 2));
  const auto *v1 = static_cast<const nimbus_guiding_v1_t *>(g->get_interface(g, NIMBUS_IFACE_GUIDING, 1));
  // Every rev 2 member came with rev 2, and rev 1's with 1.0: a smaller table is not one.
  if (v2 && v2->struct_size < sizeof(nimbus_guiding_v2_t)) v2 = nullptr;
  if (v1 && v1->struct_size < sizeof(nimbus_guiding_v1_t)) v1 = nullptr;
  if (!v1 && !v2)
    return Error{"plugin '" + id + "' does not provide " + NIMBUS_IFACE_GUIDING +
                 "@2 or @1 (complete tables)"};
  p.guide = std::move(guide).value();
  p.guide_v1 = v1, p.guide_v2 = v2;
  return Ok{};
}

// Where the scene first moves over the shutter ("file:line:column: motion"), or empty when it holds still.
std::string first_motion(const SceneDesc &scene) {
  const auto moves = [](const std::shared_ptr<const MotionTransform> &m) { return m && m->moves(); };
  for (const ShapeDesc &shape : scene.shapes)
    if (moves(shape.motion) || shape.mesh.deforms())
      return shape.where.text() + ": " + (shape.motion ? "motion" : "deform");
  for (const LightDesc &light : scene.lights)
    if (moves(light.motion)) return light.where.text() + ": motion";
  if (moves(scene.camera.motion)) return scene.path + ": camera.motion";
  return {};
}

}  // namespace

Expected<BoundPlugins> bind_plugins(PluginRegistry &registry, const RenderJob &job, uint32_t light_count,
                                    const nimbus_host_t *host) {
  BoundPlugins p;
  auto integrator = registry.instantiate(job.integrator, NIMBUS_KIND_INTEGRATOR, host);
  if (!integrator) return Error{job.scene->path + ": integrator: " + integrator.error().message};
  p.integrator = std::move(integrator).value();
  // A scene that moves renders only with an integrator that gives its paths times (SDK 1.7): any other
  // would render everything where it is when the shutter opens.
  // Likewise a scene with a dispersive glass needs an integrator that gives its paths wavelengths: any
  // other would render the glass at its index for the d line, without a rainbow.
  for (const MaterialDesc &m : job.scene->materials)
    if (m.dispersive() && !p.integrator.record().has_feature("dispersion"))
      return Error{
          m.where.text() + ": integrator '" + p.integrator.id() +
          "' does not render dispersion (no \"dispersion\" feature); give the glass a constant index "
          "or choose an integrator that has it"};
  if (const std::string moving = first_motion(*job.scene);
      !moving.empty() && !p.integrator.record().has_feature("motion-blur"))
    return Error{moving + ": integrator '" + p.integrator.id() +
                 "' does not render motion blur (no \"motion-blur\" feature); remove the motion or choose an "
                 "integrator that has it"};
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
  if (Status s = bind_guide(registry, job, host, p); !s) return s.error();
  std::vector<OptionRequest> requests;
  for (const auto &o : job.integrator_options) requests.push_back({o.name, o.value, o.where, o.hint});
  auto options = resolve_options(p.integrator.id(), p.integrator.record().options, requests);
  if (!options) return options.error();
  p.options = std::move(options.value());
  return p;
}

Status prepare_plugins(const BoundPlugins &p, const RenderJob &job, const World &world, uint32_t worker_count,
                       HookWatch &hooks) {
  nimbus_scene_info_t scene_info{};
  scene_info.header = {sizeof(scene_info), NIMBUS_S_TYPE_SCENE_INFO, nullptr};
  scene_info.light_count = world.lights.count();
  scene_info.worker_count = worker_count;
  world.geometry->sphere_center().store(scene_info.scene_center);
  scene_info.scene_radius = world.geometry->sphere_radius();
  nimbus_status_t s = NIMBUS_OK;
  {
    HookScope hook(hooks, p.sampler.id(), "prepare");
    s = p.ls->prepare(p.sampler.get(), &scene_info);
  }
  if (s != NIMBUS_OK)
    return Error{"light sampler '" + p.sampler.id() + "' failed in prepare: " + status_text(s)};
  if (p.guide.get()) {
    const auto prepare = p.guide_v2 ? p.guide_v2->prepare : p.guide_v1->prepare;
    {
      HookScope hook(hooks, p.guide.id(), "prepare");
      s = prepare(p.guide.get(), &scene_info);
    }
    if (s != NIMBUS_OK) return Error{"guide '" + p.guide.id() + "' failed in prepare: " + status_text(s)};
  }

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
  setup.guide = p.guide.get();
  setup.guide_iface = p.guide_v1;
  {
    HookScope hook(hooks, p.integrator.id(), "prepare");
    s = p.it->prepare(p.integrator.get(), &setup);
  }
  if (s != NIMBUS_OK)
    return Error{"integrator '" + p.integrator.id() + "' failed in prepare: " + status_text(s)};
  return Ok{};
}

}  // namespace nimbus
