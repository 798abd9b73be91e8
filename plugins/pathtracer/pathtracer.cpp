// nimbus.pt: unidirectional path tracing with next-event estimation, multiple importance sampling
// (power heuristic) between BSDF and light sampling, and Russian roulette. The baseline every other
// integrator is measured against (pbrt-v4's PathIntegrator is the model).
#include <nimbus/nimbus.hpp>

#include "core/math.hpp"
#include "core/sampling.hpp"
#include "sample_record.hpp"

namespace nimbus::pt {
namespace {

const char *const kRequired[] = {"nimbus.host.scene-query@1",
                                 "nimbus.host.camera@1",
                                 "nimbus.host.bsdf@1",
                                 "nimbus.host.lights@1",
                                 "nimbus.host.film@1",
                                 "nimbus.host.rng@1",
                                 nullptr};
const char *const kFeatures[] = {"progressive", "lightmix", nullptr};

// Random-number streams of a camera sample (one pixel, one iteration).
constexpr uint64_t kStreamCamera = 0;

class PathTracer final : public sdk::Integrator {
 public:
  NIMBUS_DESCRIPTOR("nimbus.pt", "Path tracer (NEE + MIS)", "Nimbus", NIMBUS_KIND_INTEGRATOR, 1, 0, 0,
                    kFeatures, kRequired)

  nimbus_status_t init() override {
    scene_ = host().service<nimbus_host_scene_query_v1_t>(NIMBUS_SERVICE_SCENE_QUERY);
    camera_ = host().service<nimbus_host_camera_v1_t>(NIMBUS_SERVICE_CAMERA);
    bsdf_ = host().service<nimbus_host_bsdf_v1_t>(NIMBUS_SERVICE_BSDF);
    lights_ = host().service<nimbus_host_lights_v1_t>(NIMBUS_SERVICE_LIGHTS);
    film_ = host().service<nimbus_host_film_v1_t>(NIMBUS_SERVICE_FILM);
    rng_ = host().service<nimbus_host_rng_v1_t>(NIMBUS_SERVICE_RNG);
    lightmix_ = host().service<nimbus_ext_lightmix_v1_t>(NIMBUS_EXT_LIGHTMIX);  // optional
    return scene_ && camera_ && bsdf_ && lights_ && film_ && rng_ &&
                   NIMBUS_HAS_MEMBER(camera_, nimbus_host_camera_v1_t, sample_film)
               ? NIMBUS_OK
               : NIMBUS_E_UNSUPPORTED;
  }

  nimbus_status_t prepare(const nimbus_render_setup_t &setup) override {
    const nimbus_host_t *h = host().get();
    max_depth_ = setup.max_depth;
    sampler_ = setup.light_sampler;
    sampler_iface_ = setup.light_sampler_iface;
    if (!sampler_ || !sampler_iface_) return NIMBUS_E_INVALID_ARG;
    infinite_.clear();
    light_group_.clear();
    const uint32_t n = lights_->count(h);
    for (uint32_t i = 0; i < n; ++i) {
      nimbus_light_info_t info{};
      info.header.struct_size = sizeof(info);
      if (lights_->info(h, i, &info) != NIMBUS_OK) return NIMBUS_E_INTERNAL;
      if (info.flags & NIMBUS_LIGHT_INFINITE) infinite_.push_back(i);
      light_group_.push_back(info.group);
    }
    registered_ = {};
    registered_.direct = film_->register_element(h, "direct", 3, NIMBUS_ELEMENT_AVERAGE);
    registered_.indirect = film_->register_element(h, "indirect", 3, NIMBUS_ELEMENT_AVERAGE);
    registered_.emission = film_->register_element(h, "emission", 3, NIMBUS_ELEMENT_AVERAGE);
    registered_.albedo = film_->register_element(h, "albedo", 3, NIMBUS_ELEMENT_AVERAGE);
    registered_.normal = film_->register_element(h, "normal", 3, NIMBUS_ELEMENT_AVERAGE);
    registered_.depth = film_->register_element(h, "depth", 1, NIMBUS_ELEMENT_AVERAGE);
    return NIMBUS_OK;
  }

  nimbus_status_t begin_render(const nimbus_render_info_t &info) override {
    // Requests are known now: keep only the ids of active elements, so unrequested work is skipped.
    const nimbus_host_t *h = host().get();
    const auto active = [&](nimbus_element_t e) {
      return film_->is_active(h, e) ? e : NIMBUS_ELEMENT_INVALID;
    };
    ids_.direct = active(registered_.direct);
    ids_.indirect = active(registered_.indirect);
    ids_.emission = active(registered_.emission);
    ids_.albedo = active(registered_.albedo);
    ids_.normal = active(registered_.normal);
    ids_.depth = active(registered_.depth);
    ids_.split_light = ids_.direct >= 0 || ids_.indirect >= 0 || ids_.emission >= 0;
    ids_.lightmix = lightmix_ && lightmix_->is_active(h);
    records_.resize(info.worker_count);
    return NIMBUS_OK;
  }

  nimbus_status_t render_tile(const nimbus_thread_ctx_t &ctx, const nimbus_tile_t &tile) override {
    const nimbus_host_t *h = host().get();
    uint32_t width = 0, height = 0;
    camera_->resolution(h, &width, &height);
    SampleRecord &rec = records_[ctx];
    for (uint32_t y = tile.y0; y < tile.y1; ++y)
      for (uint32_t x = tile.x0; x < tile.x1; ++x) {
        nimbus_rng_t rng;
        rng_->derive(h, uint64_t(y) * width + x, tile.iteration, kStreamCamera, &rng);
        rec.reset();
        trace_pixel(ctx, x, y, rng, rec);
        write(ctx, x, y, rec);
      }
    return NIMBUS_OK;
  }

 private:
  static float next(nimbus_rng_t &r) { return nimbus_rng_next_float(&r); }

  void write(const nimbus_thread_ctx_t &ctx, uint32_t x, uint32_t y, const SampleRecord &rec) const {
    const nimbus_host_t *h = host().get();
    const auto put = [&](nimbus_element_t e, const Rgb &v) {
      if (e < 0) return;
      float a[3];
      v.store(a);
      film_->accumulate(h, &ctx, e, x, y, a);
    };
    put(NIMBUS_ELEMENT_BEAUTY, rec.beauty);
    put(ids_.direct, rec.direct);
    put(ids_.indirect, rec.indirect);
    put(ids_.emission, rec.emission);
    put(ids_.albedo, rec.albedo);
    put(ids_.normal, rec.normal);
    if (ids_.depth >= 0) film_->accumulate(h, &ctx, ids_.depth, x, y, &rec.depth);
    for (const auto &[g, v] : rec.groups) {
      float a[3];
      v.store(a);
      lightmix_->accumulate(h, &ctx, g, x, y, a);
    }
  }

  void trace_pixel(const nimbus_thread_ctx_t &ctx, uint32_t x, uint32_t y, nimbus_rng_t &rng,
                   SampleRecord &rec) const {
    const nimbus_host_t *h = host().get();
    const float uf[2] = {next(rng), next(rng)};
    nimbus_camera_sample_t cs{{0, 0}, {next(rng), next(rng)}};
    const float filter_weight = camera_->sample_film(h, x, y, uf, cs.film);
    nimbus_ray_t ray;
    const float cam_weight = camera_->generate_ray(h, &cs, &ray) * filter_weight;
    if (cam_weight == 0) return;

    Rgb beta(cam_weight);
    bool specular = true;  // the previous bounce was delta (or there was none): no MIS on hits
    // The albedo element takes the first non-specular surface; no host call when nobody asked for it.
    bool albedo_done = ids_.albedo < 0;
    float prev_pdf = 0;           // solid-angle pdf of the BSDF sample that produced `ray`
    nimbus_interaction_t prev{};  // the vertex `ray` left
    // `segments` counts the segments of the path up to the vertex `ray` reaches.
    for (uint32_t segments = 1;; ++segments) {
      nimbus_hit_t hit;
      scene_->intersect(h, &ctx, &ray, &hit, 1);
      const Vec3f dir = Vec3f::load(ray.dir);
      if (hit.geom_id == NIMBUS_NONE) {
        add_infinite(rec, beta, prev, dir, specular, prev_pdf, segments);
        break;
      }
      nimbus_interaction_t ix;
      scene_->interaction(h, &ray, &hit, &ix);
      const Vec3f wo = -dir;
      if (segments == 1) {
        rec.normal = Vec3f::load(ix.ns);
        rec.depth = hit.t;
      }

      if (ix.flags & NIMBUS_IX_EMISSIVE) {
        float le[3], wo_arr[3];
        wo.store(wo_arr);
        lights_->eval_emitted(h, &ix, wo_arr, le);
        const Rgb Le = Rgb::load(le);
        if (!is_black(Le)) {
          float w = 1;
          if (!specular) {
            const float light_pdf = sampler_iface_->pmf(sampler_, &prev, ix.light_id) *
                                    lights_->pdf_incident(h, ix.light_id, &prev, ray.dir, &ix);
            w = power_heuristic(prev_pdf, light_pdf);
          }
          rec.add(beta * Le * w, light_group_[ix.light_id], segments, ids_);
        }
      }

      const nimbus_lobe_t lobes = bsdf_->lobes(h, &ix);
      const bool smooth_only = !(lobes & (NIMBUS_LOBE_DIFFUSE | NIMBUS_LOBE_GLOSSY));
      if (!albedo_done && !smooth_only) {
        float a[3], wo_arr[3];
        wo.store(wo_arr);
        bsdf_->albedo(h, &ix, wo_arr, a);
        rec.albedo = beta / cam_weight * Rgb::load(a);
        albedo_done = true;
      }
      if (segments >= max_depth_) break;

      if (!smooth_only) direct_light(ctx, ix, wo, rng, beta, segments + 1, rec);

      // Continue the path by sampling the BSDF.
      float wo_arr[3], u[3] = {next(rng), next(rng), next(rng)};
      wo.store(wo_arr);
      nimbus_bsdf_sample_t bs;
      bsdf_->sample(h, &ix, wo_arr, u, NIMBUS_MODE_RADIANCE, &bs);
      if (!(bs.pdf > 0)) break;
      const Vec3f wi = Vec3f::load(bs.wi);
      beta *= Rgb::load(bs.f) * (std::abs(dot(wi, Vec3f::load(ix.ns))) / bs.pdf);
      if (is_black(beta) || !is_finite(beta)) break;
      specular = (bs.lobe & NIMBUS_LOBE_SPECULAR) != 0;
      prev_pdf = bs.pdf;
      prev = ix;

      // Russian roulette after three segments, on the throughput (as pbrt-v4).
      if (segments >= 3) {
        const float q = std::max(0.0f, 1 - max_component(beta));
        if (next(rng) < q) break;
        beta /= 1 - q;
      }
      scene_->spawn_ray(h, &ix, bs.wi, kInfinity, &ray);
    }
  }

  // Radiance from infinite lights along an escaped ray, MIS-weighted against light sampling.
  void add_infinite(SampleRecord &rec, const Rgb &beta, const nimbus_interaction_t &prev, const Vec3f &dir,
                    bool specular, float prev_pdf, uint32_t segments) const {
    float d[3];
    dir.store(d);
    for (uint32_t l : infinite_) {
      float le[3];
      lights_->eval_infinite(host().get(), l, d, le);
      const Rgb Le = Rgb::load(le);
      if (is_black(Le)) continue;
      float w = 1;
      if (!specular) {
        const float light_pdf = sampler_iface_->pmf(sampler_, &prev, l) *
                                lights_->pdf_incident(host().get(), l, &prev, d, nullptr);
        w = power_heuristic(prev_pdf, light_pdf);
      }
      rec.add(beta * Le * w, light_group_[l], segments, ids_);
    }
  }

  // Next-event estimation: one light chosen by the light sampler, MIS-weighted against BSDF sampling.
  void direct_light(const nimbus_thread_ctx_t &ctx, const nimbus_interaction_t &ix, const Vec3f &wo,
                    nimbus_rng_t &rng, const Rgb &beta, uint32_t segments, SampleRecord &rec) const {
    const nimbus_host_t *h = host().get();
    const float u_pick = next(rng);
    const float u_light[2] = {next(rng), next(rng)};
    float pmf = 0;
    const uint32_t light = sampler_iface_->pick(sampler_, &ix, u_pick, &pmf);
    if (light == NIMBUS_NONE || !(pmf > 0)) return;
    nimbus_light_incident_t ls;
    lights_->sample_incident(h, light, &ix, u_light, &ls);
    if (!(ls.pdf > 0)) return;
    const Rgb Li = Rgb::load(ls.L);
    if (is_black(Li)) return;
    float wo_arr[3], f[3], bsdf_pdf = 0;
    wo.store(wo_arr);
    bsdf_->eval(h, &ix, wo_arr, ls.wi, NIMBUS_MODE_RADIANCE, f, &bsdf_pdf, nullptr);
    const Vec3f wi = Vec3f::load(ls.wi);
    const Rgb contrib = Rgb::load(f) * std::abs(dot(wi, Vec3f::load(ix.ns)));
    if (is_black(contrib)) return;
    nimbus_ray_t shadow;
    scene_->spawn_ray_to(h, &ix, ls.p, &shadow);
    if (ls.flags & NIMBUS_LIGHT_INFINITE) shadow.tfar = kInfinity;
    uint8_t blocked = 0;
    scene_->occluded(h, &ctx, &shadow, &blocked, 1);
    if (blocked) return;
    const bool delta = (ls.flags & (NIMBUS_LIGHT_DELTA_POSITION | NIMBUS_LIGHT_DELTA_DIRECTION)) != 0;
    const float light_pdf = pmf * ls.pdf;
    const float w = delta ? 1.0f : power_heuristic(light_pdf, bsdf_pdf);
    rec.add(beta * contrib * Li * (w / light_pdf), light_group_[light], segments, ids_);
  }

  const nimbus_host_scene_query_v1_t *scene_ = nullptr;
  const nimbus_host_camera_v1_t *camera_ = nullptr;
  const nimbus_host_bsdf_v1_t *bsdf_ = nullptr;
  const nimbus_host_lights_v1_t *lights_ = nullptr;
  const nimbus_host_film_v1_t *film_ = nullptr;
  const nimbus_host_rng_v1_t *rng_ = nullptr;
  const nimbus_plugin_t *sampler_ = nullptr;
  const nimbus_light_sampler_v1_t *sampler_iface_ = nullptr;
  const nimbus_ext_lightmix_v1_t *lightmix_ = nullptr;
  uint32_t max_depth_ = 16;
  std::vector<uint32_t> infinite_;
  std::vector<uint32_t> light_group_;  // LightMix group of each light
  ElementIds registered_, ids_;        // all registered elements; the active ones
  sdk::PerWorker<SampleRecord> records_;
};

}  // namespace
}  // namespace nimbus::pt

NIMBUS_PLUGIN_LIBRARY(nimbus::pt::PathTracer)
