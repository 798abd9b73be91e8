// nimbus.lt: light tracing. Particles leave the lights and every non-delta vertex is connected to the
// camera (splatted into the film); lights seen directly come from connecting the emission point. An
// independent, consistent estimator that renders caustics from point and small lights seen directly,
// which path tracing cannot: the reference for such scenes. It shares no transport code with nimbus.pt
// beyond the host's BSDFs, lights and camera.
//
// Each iteration traces as many light paths as the image has pixels, so one iteration's splats
// estimate the whole image once (the film divides by the iteration count).
#include <nimbus/nimbus.hpp>

#include <nimbus/cpp/math.hpp>
#include <nimbus/cpp/path_services.hpp>
#include <nimbus/cpp/spectral_path.hpp>

namespace nimbus::lt {
namespace {

const char *const kRequired[] = {
    "nimbus.host.scene-query@1", "nimbus.host.camera@1", "nimbus.host.bsdf@1",  "nimbus.host.lights@1",
    "nimbus.host.film@1",        "nimbus.host.rng@1",    "nimbus.host.tasks@1", nullptr};
// motion-blur: every light path draws a time when something moves (SDK 1.7), at which it leaves its
// light and meets the camera; dispersion: a wavelength past a dispersive glass (SDK 1.7).
const char *const kFeatures[] = {"progressive", "lightmix", "motion-blur", "dispersion", nullptr};

constexpr uint64_t kStreamLightPath = 1;  // distinct from the camera streams of other integrators
constexpr uint64_t kPathsPerTask = 1024;

class LightTracer final : public sdk::Integrator {
 public:
  NIMBUS_DESCRIPTOR("nimbus.lt", "Light tracer (reference for caustics)", "Nimbus", NIMBUS_KIND_INTEGRATOR, 1,
                    0, 0, kFeatures, kRequired)

  nimbus_status_t init() override {
    scene_ = host().service<nimbus_host_scene_query_v1_t>(NIMBUS_SERVICE_SCENE_QUERY);
    camera_ = host().service<nimbus_host_camera_v1_t>(NIMBUS_SERVICE_CAMERA);
    bsdf_ = host().service<nimbus_host_bsdf_v1_t>(NIMBUS_SERVICE_BSDF);
    lights_ = host().service<nimbus_host_lights_v1_t>(NIMBUS_SERVICE_LIGHTS);
    film_ = host().service<nimbus_host_film_v1_t>(NIMBUS_SERVICE_FILM);
    rng_ = host().service<nimbus_host_rng_v1_t>(NIMBUS_SERVICE_RNG);
    tasks_ = host().service<nimbus_host_tasks_v1_t>(NIMBUS_SERVICE_TASKS);
    lightmix_ = host().service<nimbus_ext_lightmix_v1_t>(NIMBUS_EXT_LIGHTMIX);
    const bool ok = scene_ && camera_ && bsdf_ && lights_ && film_ && rng_ && tasks_ &&
                    NIMBUS_HAS_MEMBER(camera_, nimbus_host_camera_v1_t, connect);
    return ok ? NIMBUS_OK : NIMBUS_E_UNSUPPORTED;
  }

  nimbus_status_t prepare(const nimbus_render_setup_t &setup) override {
    max_depth_ = setup.max_depth;
    sampler_ = setup.light_sampler;
    sampler_iface_ = setup.light_sampler_iface;
    if (!sampler_ || !sampler_iface_) return NIMBUS_E_INVALID_ARG;
    light_group_.clear();
    const uint32_t n = lights_->count(host().get());
    for (uint32_t i = 0; i < n; ++i) {
      nimbus_light_info_t info{};
      info.header.struct_size = sizeof(info);
      if (lights_->info(host().get(), i, &info) != NIMBUS_OK) return NIMBUS_E_INTERNAL;
      light_group_.push_back(info.group);
    }
    timed_ = sdk::TimedScene::of(host().get(), scene_, camera_, lights_);
    spectral_ = sdk::PathSpectrum::needed(host());  // wavelengths only in a dispersive scene
    // Beauty takes splats: register it with the splat flag (it is always active).
    film_->register_element(host().get(), "beauty", 3, NIMBUS_ELEMENT_SPLAT);
    return NIMBUS_OK;
  }

  nimbus_status_t begin_render(const nimbus_render_info_t &) override {
    uint32_t w = 0, h = 0;
    camera_->resolution(host().get(), &w, &h);
    paths_ = uint64_t(w) * h;
    lightmix_active_ = lightmix_ && lightmix_->is_active(host().get());
    return NIMBUS_OK;
  }

  // All the work happens in the light pass; camera tiles have nothing to do.
  nimbus_status_t begin_iteration(uint64_t iteration) override {
    iteration_ = iteration;
    const auto fn = [](const nimbus_thread_ctx_t *ctx, uint64_t begin, uint64_t end, void *user) {
      auto *self = static_cast<LightTracer *>(user);
      for (uint64_t p = begin; p < end; ++p) self->trace_light_path(*ctx, p);
    };
    return tasks_->parallel_for(host().get(), paths_, kPathsPerTask, fn, this);
  }

  nimbus_status_t render_tile(const nimbus_thread_ctx_t &, const nimbus_tile_t &) override {
    return NIMBUS_OK;
  }

 private:
  static float next(nimbus_rng_t &r) { return nimbus_rng_next_float(&r); }

  void splat(const nimbus_thread_ctx_t &ctx, const float raster[2], const Rgb &v, uint32_t light) const {
    if (!is_finite(v) || is_black(v)) return;
    float a[3];
    v.store(a);
    film_->splat(host().get(), &ctx, NIMBUS_ELEMENT_BEAUTY, raster[0], raster[1], a);
    if (lightmix_active_) lightmix_->splat(host().get(), &ctx, light_group_[light], raster[0], raster[1], a);
  }

  // Connects point p (with the given outgoing radiance towards the lens per unit W) to the camera.
  bool camera_visible(const nimbus_thread_ctx_t &ctx, const nimbus_interaction_t *ix, const Vec3f &p,
                      const float lens_point[3], float time) const {
    if (ix) return !timed_.occluded_to(host().get(), ctx, *ix, lens_point, false, time);
    const Vec3f d = Vec3f::load(lens_point) - p;
    const float dist = length(d);
    nimbus_ray_t ray;
    p.store(ray.org);
    (d / dist).store(ray.dir);
    ray.tnear = 0;
    ray.tfar = dist * (1 - 1e-4f);
    ray.mask = ~0u, ray.flags = 0;
    return !timed_.occluded(host().get(), ctx, ray, time);
  }

  void trace_light_path(const nimbus_thread_ctx_t &ctx, uint64_t path) const {
    const nimbus_host_t *h = host().get();
    nimbus_rng_t rng;
    rng_->derive(h, path, iteration_, kStreamLightPath, &rng);
    float pmf = 0;
    const uint32_t light = sampler_iface_->pick_emitter(sampler_, next(rng), &pmf);
    if (light == NIMBUS_NONE || !(pmf > 0)) return;
    const float ue[4] = {next(rng), next(rng), next(rng), next(rng)};
    // A time from the shutter's curve when something moves (the film integrates over it: weight 1);
    // no number is drawn otherwise, so a static scene's paths are unchanged.
    const float time = timed_.time(h, timed_.timed ? next(rng) : 0.0f);
    nimbus_light_emission_t em;
    timed_.sample_emission(h, light, ue, time, em);
    if (!(em.pdf_pos > 0) || !(em.pdf_dir > 0)) return;
    const float inv_paths = 1.0f / float(paths_);
    const Vec3f org = Vec3f::load(em.org), n = Vec3f::load(em.n), dir = Vec3f::load(em.dir);
    const Rgb Le = Rgb::load(em.Le);

    // Emitters seen directly: connect the emission point (area lights only; delta positions and
    // infinite lights cannot be seen by a pinhole).
    if ((em.flags & NIMBUS_LIGHT_AREA) && max_depth_ >= 1) {
      const float lens_u[2] = {next(rng), next(rng)};
      float raster[2], lens[3];
      const float we = timed_.connect(h, em.org, time, lens_u, raster, lens);
      const Vec3f to_cam = normalize(Vec3f::load(lens) - org);
      // One-sided emitters are seen only from the side their normal faces; two-sided ones from both,
      // whichever side this photon happened to leave from.
      const float cos_l = (em.flags & NIMBUS_LIGHT_TWO_SIDED) ? std::abs(dot(n, to_cam)) : dot(n, to_cam);
      if (we > 0 && cos_l > 0) {
        // Offset the origin off the emitter, on the camera's side.
        const Vec3f o = org + n * (dot(n, to_cam) >= 0 ? relative_offset(org) : -relative_offset(org));
        if (camera_visible(ctx, nullptr, o, lens, time))
          splat(ctx, raster, Le * (cos_l * we * inv_paths / (pmf * em.pdf_pos)), light);
      }
    }

    const bool delta_pos = em.flags & NIMBUS_LIGHT_DELTA_POSITION;
    const float cos_e = delta_pos || (em.flags & NIMBUS_LIGHT_INFINITE) ? 1.0f : std::abs(dot(n, dir));
    Rgb beta = Le * (cos_e / (pmf * em.pdf_pos * em.pdf_dir));
    const float beta_emitted = max_component(beta);
    sdk::PathSpectrum spectrum(h, spectral_, bsdf_);  // RGB until a dispersive vertex
    // The segment along `along` reaches `hit`, and `ix` if it hits; after the emission ray, trace_from
    // makes each segment in one host call.
    const nimbus_ray_t ray = sdk::emission_ray(org, dir, em.flags);
    nimbus_hit_t hit;
    nimbus_interaction_t ix;
    timed_.trace(h, ctx, ray, time, hit, ix);
    Vec3f along = dir;

    // Vertex i (1-based) closes a path of i + 1 segments with the camera connection.
    for (uint32_t i = 1; i + 1 <= max_depth_; ++i) {
      if (hit.geom_id == NIMBUS_NONE) return;
      const Vec3f wo = -along;
      float wo_arr[3];
      wo.store(wo_arr);
      const nimbus_lobe_t lobes = bsdf_->lobes(h, &ix);
      spectrum.disperse(
          lobes, [&] { return next(rng); }, beta);
      const Vec3f p = Vec3f::load(ix.p), ns = Vec3f::load(ix.ns);

      if (lobes & (NIMBUS_LOBE_DIFFUSE | NIMBUS_LOBE_GLOSSY)) {
        const float lens_u[2] = {next(rng), next(rng)};
        float raster[2], lens[3];
        const float we = timed_.connect(h, ix.p, time, lens_u, raster, lens);
        if (we > 0) {
          const Vec3f wc = normalize(Vec3f::load(lens) - p);
          float wc_arr[3], f[3];
          wc.store(wc_arr);
          spectrum.eval(&ix, wo_arr, wc_arr, NIMBUS_MODE_IMPORTANCE, f, nullptr, nullptr);
          const Rgb c = beta * Rgb::load(f) * (std::abs(dot(ns, wc)) * we * inv_paths);
          if (!is_black(c) && camera_visible(ctx, &ix, p, lens, time)) splat(ctx, raster, c, light);
        }
      } else {
        next(rng), next(rng);  // keep the stream layout independent of the material
      }

      const float u[3] = {next(rng), next(rng), next(rng)};
      nimbus_bsdf_sample_t bs;
      spectrum.sample(&ix, wo_arr, u, NIMBUS_MODE_IMPORTANCE, &bs);
      if (!(bs.pdf > 0)) return;
      const Vec3f wi = Vec3f::load(bs.wi);
      beta *= Rgb::load(bs.f) * (std::abs(dot(wi, ns)) / bs.pdf);
      if (is_black(beta) || !is_finite(beta)) return;
      if (i >= 3) {
        // Russian roulette on the throughput since emission (as the path tracer's, which starts at 1):
        // beta itself carries the emitted power, whose units scale with the scene (area, distance^2).
        const float q = std::max(0.0f, 1 - max_component(beta / beta_emitted));
        if (next(rng) < q) return;
        beta /= 1 - q;
      }
      timed_.trace_from(h, ctx, ix, bs.wi, time, hit, ix);
      along = wi;
    }
  }

  const nimbus_host_scene_query_v1_t *scene_ = nullptr;
  sdk::TimedScene timed_;  // the scene at a light path's time when something moves
  const nimbus_host_spectral_v1_t *spectral_ = nullptr;  // null unless the scene disperses light
  const nimbus_host_camera_v1_t *camera_ = nullptr;
  const nimbus_host_bsdf_v1_t *bsdf_ = nullptr;
  const nimbus_host_lights_v1_t *lights_ = nullptr;
  const nimbus_host_film_v1_t *film_ = nullptr;
  const nimbus_host_rng_v1_t *rng_ = nullptr;
  const nimbus_host_tasks_v1_t *tasks_ = nullptr;
  const nimbus_ext_lightmix_v1_t *lightmix_ = nullptr;
  const nimbus_plugin_t *sampler_ = nullptr;
  const nimbus_light_sampler_v1_t *sampler_iface_ = nullptr;
  uint32_t max_depth_ = 16;
  uint64_t paths_ = 0, iteration_ = 0;
  bool lightmix_active_ = false;
  std::vector<uint32_t> light_group_;
};

}  // namespace
}  // namespace nimbus::lt

NIMBUS_PLUGIN_LIBRARY(nimbus::lt::LightTracer)
