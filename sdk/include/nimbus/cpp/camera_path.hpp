// The camera-path layer of integrators (pbrt-v4's RayIntegrator, Mitsuba 3's SamplingIntegrator): the
// pixel loop, the film write, element registration and activation, the sample record, next-event
// estimation with MIS and the MIS of emitter hits, for unidirectional paths with throughput Russian
// roulette. An integrator derives from CameraPathIntegrator<Self, Record> and supplies only what differs,
// as a path extension whose hooks the camera path calls (PlainPath: nimbus.pt's estimator, power-heuristic
// MIS between BSDF and light sampling). Requires C++20.
//
//   class MyIntegrator final : public nimbus::sdk::CameraPathIntegrator<MyIntegrator> {
//    public:
//     NIMBUS_DESCRIPTOR(...)
//     void sample(const nimbus_thread_ctx_t &ctx, uint32_t x, uint32_t y, nimbus_rng_t &rng,
//                 nimbus::sdk::SampleRecord &rec) const {
//       nimbus::sdk::PlainPath path;
//       trace(ctx, x, y, rng, rec, path);
//     }
//   };
#pragma once

#include <nimbus/nimbus.hpp>

#include <vector>

#include <nimbus/cpp/film_elements.hpp>
#include <nimbus/cpp/light_selection.hpp>
#include <nimbus/cpp/math.hpp>
#include <nimbus/cpp/path_services.hpp>
#include <nimbus/cpp/rng.hpp>
#include <nimbus/cpp/sample_record.hpp>
#include <nimbus/cpp/sampling.hpp>
#include <nimbus/cpp/spectral_path.hpp>

namespace nimbus::sdk {

// What an extension's weight hooks return: the MIS weight of a contribution, whether the integrator's
// own element takes it (SampleRecord::add's `divert`), and the contribution's weight under a second
// combination of techniques as a ratio to w, for a record that measures one against the other
// (SampleRecord::add's `alt_ratio`; the caustics solver's light-path trial).
struct PathWeight {
  float w = 1;
  bool divert = false;
  float alt_ratio = 1;
};

// Light a BSDF-sampled ray found: an emitter it hit, or an infinite light it escaped to.
struct LightHit {
  uint32_t light = 0;
  bool specular = false;  // the bounce before was delta (or there was none): light_pdf is unset
  float bsdf_pdf = 0;     // solid-angle pdf of that bounce
  float light_pdf = 0;    // the light sampler's pmf times the light's solid-angle pdf, from prev
  Vec3f p, n;             // the emitter point and its normal (zero for infinite lights)
  Vec3f wo;               // towards the previous vertex (for infinite lights: minus the direction)
  const nimbus_interaction_t *prev = nullptr;  // the vertex the ray left
  uint32_t segments = 0;                       // segments of the path up to the light
  float time = 0;                              // the path's scene time (0 when nothing moves)
};

// A light sample that reached vertex `ix` unoccluded.
struct LightSample {
  uint32_t light = 0;
  const nimbus_interaction_t *ix = nullptr;
  const nimbus_light_incident_t *ls = nullptr;
  Vec3f wi;                // towards the light
  float pmf = 0;           // the light sampler's probability of this light
  float light_pdf = 0;     // pmf times ls->pdf
  float bsdf_pdf = 0;      // BSDF pdf of wi
  float bsdf_pdf_rev = 0;  // reverse BSDF pdf (only when the extension asks for it)
  bool delta = false;      // a delta light (position or direction)
  uint32_t segments = 0;   // length of the path it completes
  float time = 0;          // the path's scene time (0 when nothing moves)
};

// A rough or sharp surface vertex of the camera path, before it scatters.
struct PathVertex {
  const nimbus_thread_ctx_t *ctx = nullptr;
  const nimbus_interaction_t *ix = nullptr;
  Vec3f wo;
  nimbus_lobe_t lobes = 0;
  Rgb beta;
  uint32_t segments = 0;  // segments of the path up to this vertex
  float time = 0;         // the path's scene time (0 when nothing moves)
  float time_u = 0;       // the uniform number it was drawn from: the share of the exposure before it
  float lambda = 0;       // the path's wavelength (nm) after a dispersive vertex; 0 while RGB
};

// nimbus.pt's estimator: power-heuristic MIS between BSDF and light sampling, nothing else.
struct PlainPath {
  static constexpr bool kReversePdfs = false;  // NEE evaluates no reverse BSDF pdf
  void arrive(float /*t*/, const nimbus_interaction_t & /*ix*/, const Vec3f & /*dir*/) {}
  PathWeight hit(const LightHit &h) const {
    return {h.specular ? 1.0f : power_heuristic(h.bsdf_pdf, h.light_pdf), false};
  }
  template <class Record>
  void vertex(const PathVertex &, Record &) {}
  PathWeight nee(const LightSample &s) const {
    return {s.delta ? 1.0f : power_heuristic(s.light_pdf, s.bsdf_pdf), false};
  }
  void scatter(const nimbus_interaction_t &, const Vec3f & /*wi*/, const nimbus_bsdf_sample_t &, uint32_t) {}
};

template <class Self, class Record = SampleRecord>
class CameraPathIntegrator : public Integrator {
 public:
  nimbus_status_t init() override { return svc_.fetch(host()) ? NIMBUS_OK : NIMBUS_E_UNSUPPORTED; }

  // Binds the light sampler, reads the lights' infinite flags and LightMix groups, registers the
  // elements. An integrator that overrides it calls it first.
  nimbus_status_t prepare(const nimbus_render_setup_t &setup) override {
    const nimbus_host_t *h = host().get();
    max_depth_ = setup.max_depth;
    sampler_ = setup.light_sampler;
    sampler_iface_ = setup.light_sampler_iface;
    if (!sampler_ || !sampler_iface_) return NIMBUS_E_INVALID_ARG;
    // A sampler that learns from its samples gets every NEE outcome (light_sampler.h, record).
    record_ = NIMBUS_HAS_MEMBER(sampler_iface_, nimbus_light_sampler_v1_t, record) ? sampler_iface_->record
                                                                                   : nullptr;
    infinite_.clear();
    light_group_.clear();
    light_info_.clear();
    const uint32_t n = svc_.lights->count(h);
    for (uint32_t i = 0; i < n; ++i) {
      nimbus_light_info_t info{};
      info.header.struct_size = sizeof(info);
      if (svc_.lights->info(h, i, &info) != NIMBUS_OK) return NIMBUS_E_INTERNAL;
      if (info.flags & NIMBUS_LIGHT_INFINITE) infinite_.push_back(i);
      light_group_.push_back(info.group);
      light_info_.push_back(info);
    }
    std::vector<float> powers;
    for (const nimbus_light_info_t &info : light_info_) powers.push_back(info.power);
    selection_.prepare(sampler_, sampler_iface_, light_group_, powers);
    elements_.register_all(svc_.film, h, self().diverted_element());
    // Motion blur (SDK 1.7): a time per camera path when something moves while the shutter is open;
    // otherwise no time is drawn and the path's random numbers are those of a static scene.
    scene_ = TimedScene::of(h, svc_.scene, svc_.camera, svc_.lights);
    // Dispersion (SDK 1.7): wavelengths only in a scene with a dispersive material.
    spectral_ = PathSpectrum::needed(host());
    return NIMBUS_OK;
  }

  nimbus_status_t begin_render(const nimbus_render_info_t &info) override {
    elements_.activate(svc_.film, svc_.lightmix, host().get());
    selection_.set_lightmix(ids().lightmix);
    records_.resize(info.worker_count);
    return NIMBUS_OK;
  }

  // One sample per pixel of the tile: the stream of (pixel, iteration), the integrator's sample(), the
  // film write; tile_begins and sample_done let an integrator keep statistics.
  nimbus_status_t render_tile(const nimbus_thread_ctx_t &ctx, const nimbus_tile_t &tile) override {
    const nimbus_host_t *h = host().get();
    uint32_t width = 0, height = 0;
    svc_.camera->resolution(h, &width, &height);
    Record &rec = records_[ctx];
    self().tile_begins(ctx, tile);
    for (uint32_t y = tile.y0; y < tile.y1; ++y) {
      // Each pixel's stream is derived a pixel ahead: the hash's chain of multiplies then runs beside
      // the previous pixel's path instead of delaying its own first ray.
      nimbus_rng_t next;
      svc_.rng->derive(h, uint64_t(y) * width + tile.x0, tile.iteration, kStreamCamera, &next);
      for (uint32_t x = tile.x0; x < tile.x1; ++x) {
        nimbus_rng_t rng = next;
        if (x + 1 < tile.x1)
          svc_.rng->derive(h, uint64_t(y) * width + x + 1, tile.iteration, kStreamCamera, &next);
        rec.reset();
        self().sample(ctx, x, y, rng, rec);
        elements_.write(svc_.film, svc_.lightmix, h, ctx, x, y, rec);
        self().sample_done(ctx, x, y, rec);
      }
    }
    return NIMBUS_OK;
  }

  // Defaults of the hooks an integrator may hide with its own.
  const char *diverted_element() const { return nullptr; }  // the name of its own lighting element
  void tile_begins(const nimbus_thread_ctx_t &, const nimbus_tile_t &) {}
  void sample_done(const nimbus_thread_ctx_t &, uint32_t, uint32_t, const Record &) {}

 protected:
  // The scene as camera paths see it (timed when something moves while the shutter is open).
  const TimedScene &timed_scene() const { return scene_; }
  // The host's spectral service when the scene disperses light, else null.
  const nimbus_host_spectral_v1_t *spectral() const { return spectral_; }

  // The random-number stream of camera samples: derive(pixel, iteration, kStreamCamera).
  static constexpr uint64_t kStreamCamera = 0;

  // The camera path of pixel (x, y): a filtered film sample, then surface vertices until the path
  // leaves the scene, reaches max_depth or is stopped by Russian roulette (after three segments, on the
  // throughput, as pbrt-v4). `path` is the integrator's extension (PlainPath's hooks show the contract).
  template <class Path>
  void trace(const nimbus_thread_ctx_t &ctx, uint32_t x, uint32_t y, nimbus_rng_t &rng, Record &rec,
             Path &path) const {
    const nimbus_host_t *h = host().get();
    const float uf[2] = {next_uniform(rng), next_uniform(rng)};
    nimbus_camera_sample_t cs{{0, 0}, {next_uniform(rng), next_uniform(rng)}};
    const float filter_weight = svc_.camera->sample_film(h, x, y, uf, cs.film);
    // Drawn from the shutter's curve, which the film integrates over: the weight stays 1.
    const float time_u = scene_.timed ? next_uniform(rng) : 0.0f;
    const float time = scene_.time(h, time_u);
    nimbus_ray_t ray;
    const float cam_weight = scene_.generate_ray(h, cs, time, ray) * filter_weight;
    if (cam_weight == 0) return;

    Rgb beta(cam_weight);
    PathSpectrum spectrum(h, spectral_, svc_.bsdf);  // RGB until a dispersive vertex
    bool specular = true;  // the previous bounce was delta (or there was none): no MIS on hits
    // The albedo element takes the first non-specular surface; no host call when nobody asked for it.
    bool albedo_done = ids().albedo < 0;
    float prev_pdf = 0;           // solid-angle pdf of the BSDF sample that made the current segment
    nimbus_interaction_t prev{};  // the vertex the current segment left
    // The current segment (along dir) reaches `hit`, and `ix` if it hits; `segments` counts the path's
    // segments up to it. After the camera ray, trace_from makes each in one host call.
    nimbus_hit_t hit;
    nimbus_interaction_t ix;
    scene_.trace(h, ctx, ray, time, hit, ix);
    Vec3f dir = Vec3f::load(ray.dir);
    for (uint32_t segments = 1;; ++segments) {
      if (hit.geom_id == NIMBUS_NONE) {
        add_infinite(rec, beta, spectrum, prev, dir, specular, prev_pdf, segments, time, path);
        break;
      }
      const Vec3f wo = -dir;
      if (segments == 1) {
        rec.normal = Vec3f::load(ix.ns);
        rec.depth = hit.t;
      }
      path.arrive(hit.t, ix, dir);

      if (ix.flags & NIMBUS_IX_EMISSIVE) {
        float le[3], wo_arr[3];
        wo.store(wo_arr);
        svc_.lights->eval_emitted(h, &ix, wo_arr, le);
        const Rgb Le = spectrum.light(Rgb::load(le));
        if (!is_black(Le)) {
          float d[3];
          dir.store(d);
          LightHit lh{ix.light_id,        specular, prev_pdf, 0,        Vec3f::load(ix.p),
                      Vec3f::load(ix.ng), wo,       &prev,    segments, time};
          if (!specular)
            lh.light_pdf =
                selection_.pmf(&prev, ix.light_id) * svc_.lights->pdf_incident(h, ix.light_id, &prev, d, &ix);
          const PathWeight w = path.hit(lh);
          rec.add(beta * Le * w.w, light_group_[ix.light_id], segments, ids(), w.divert, w.alt_ratio);
        }
      }

      const nimbus_lobe_t lobes = svc_.bsdf->lobes(h, &ix);
      spectrum.disperse(
          lobes, [&] { return next_uniform(rng); }, beta);
      const bool smooth_only = !(lobes & (NIMBUS_LOBE_DIFFUSE | NIMBUS_LOBE_GLOSSY));
      if (!albedo_done && !smooth_only) {
        float a[3], wo_arr[3];
        wo.store(wo_arr);
        svc_.bsdf->albedo(h, &ix, wo_arr, a);
        rec.albedo = beta / cam_weight * Rgb::load(a);
        albedo_done = true;
      }
      path.vertex(PathVertex{&ctx, &ix, wo, lobes, beta, segments, time, time_u, spectrum.lambda()}, rec);
      if (segments >= max_depth_) break;

      // Next-event estimation, then the BSDF sample that continues the path, in the order of their random
      // numbers; the sample is taken first, so that its chain of dependent arithmetic (the next ray's
      // direction) overlaps the shadow ray's work instead of waiting for it.
      const LightNumbers nee_u = smooth_only ? LightNumbers{} : light_numbers(rng);
      float wo_arr[3], u[3] = {next_uniform(rng), next_uniform(rng), next_uniform(rng)};
      wo.store(wo_arr);
      nimbus_bsdf_sample_t bs;
      spectrum.sample(&ix, wo_arr, u, NIMBUS_MODE_RADIANCE, &bs);
      if (!smooth_only) direct_light(ctx, ix, wo, time, spectrum, nee_u, beta, segments + 1, rec, path);
      if (!(bs.pdf > 0)) break;
      const Vec3f wi = Vec3f::load(bs.wi);
      path.scatter(ix, wi, bs, segments);
      beta *= Rgb::load(bs.f) * (std::abs(dot(wi, Vec3f::load(ix.ns))) / bs.pdf);
      if (is_black(beta) || !is_finite(beta)) break;
      specular = (bs.lobe & NIMBUS_LOBE_SPECULAR) != 0;
      prev_pdf = bs.pdf;
      prev = ix;

      if (segments >= 3) {
        const float q = std::max(0.0f, 1 - max_component(beta));
        if (next_uniform(rng) < q) break;
        beta /= 1 - q;
      }
      scene_.trace_from(h, ctx, prev, bs.wi, time, hit, ix);
      dir = wi;
    }
  }

 private:
  // Radiance from infinite lights along an escaped ray, weighted by the extension.
  template <class Path>
  void add_infinite(Record &rec, const Rgb &beta, const PathSpectrum &spectrum,
                    const nimbus_interaction_t &prev, const Vec3f &dir, bool specular, float prev_pdf,
                    uint32_t segments, float time, Path &path) const {
    const nimbus_host_t *h = host().get();
    float d[3];
    dir.store(d);
    for (uint32_t l : infinite_) {
      float le[3];
      svc_.lights->eval_infinite(h, l, d, le);
      const Rgb Le = spectrum.light(Rgb::load(le));
      if (is_black(Le)) continue;
      LightHit lh{l, specular, prev_pdf, 0, Vec3f(), Vec3f(), -dir, &prev, segments, time};
      if (!specular)
        lh.light_pdf = selection_.pmf(&prev, l) * svc_.lights->pdf_incident(h, l, &prev, d, nullptr);
      const PathWeight w = path.hit(lh);
      rec.add(beta * Le * w.w, light_group_[l], segments, ids(), w.divert, w.alt_ratio);
    }
  }

  // The random numbers of one next-event estimation: the light's pick, its sample, and LightMix's group
  // mixture (drawn only with LightMix: without it, the same stream as before).
  struct LightNumbers {
    float pick = 0, light[2] = {0, 0}, mix = 0;
  };
  LightNumbers light_numbers(nimbus_rng_t &rng) const {
    LightNumbers n;
    n.pick = next_uniform(rng);
    n.light[0] = next_uniform(rng), n.light[1] = next_uniform(rng);
    n.mix = selection_.lightmix() ? next_uniform(rng) : 0.0f;
    return n;
  }

  // Next-event estimation: one light chosen by the light sampler, weighted by the extension.
  // `segments` = length of the path it completes.
  template <class Path>
  void direct_light(const nimbus_thread_ctx_t &ctx, const nimbus_interaction_t &ix, const Vec3f &wo,
                    float time, const PathSpectrum &spectrum, const LightNumbers &u, const Rgb &beta,
                    uint32_t segments, Record &rec, Path &path) const {
    const nimbus_host_t *h = host().get();
    float pmf = 0;
    const uint32_t light = selection_.pick(&ix, u.pick, u.mix, &pmf);
    if (light == NIMBUS_NONE || !(pmf > 0)) return;
    // The sample's outcome for the sampler: its contribution before selection and MIS, 0 unless it
    // reaches the vertex unoccluded.
    float outcome = 0;
    struct Report {
      const CameraPathIntegrator &self;
      const nimbus_thread_ctx_t &ctx;
      uint32_t light;
      const float &v;
      ~Report() {
        if (self.record_) self.record_(self.sampler_, &ctx, light, v);
      }
    } report{*this, ctx, light, outcome};
    nimbus_light_incident_t ls;
    scene_.sample_incident(h, light, ix, u.light, time, ls);
    if (!(ls.pdf > 0)) return;
    const Rgb Li = spectrum.light(Rgb::load(ls.L));
    if (is_black(Li)) return;
    float wo_arr[3], f[3], bsdf_pdf = 0, bsdf_pdf_rev = 0;
    wo.store(wo_arr);
    spectrum.eval(&ix, wo_arr, ls.wi, NIMBUS_MODE_RADIANCE, f, &bsdf_pdf,
                  Path::kReversePdfs ? &bsdf_pdf_rev : nullptr);
    const Vec3f wi = Vec3f::load(ls.wi);
    const Rgb contrib = Rgb::load(f) * std::abs(dot(wi, Vec3f::load(ix.ns)));
    if (is_black(contrib)) return;
    if (scene_.occluded_to(h, ctx, ix, ls.p, ls.flags & NIMBUS_LIGHT_INFINITE, time)) return;
    outcome =
        std::abs(luminance(beta * contrib * Li)) / ls.pdf;  // a wavelength's beta may have a negative channel
    const bool delta = (ls.flags & (NIMBUS_LIGHT_DELTA_POSITION | NIMBUS_LIGHT_DELTA_DIRECTION)) != 0;
    const float light_pdf = pmf * ls.pdf;
    const PathWeight w = path.nee(
        LightSample{light, &ix, &ls, wi, pmf, light_pdf, bsdf_pdf, bsdf_pdf_rev, delta, segments, time});
    rec.add(beta * contrib * Li * (w.w / light_pdf), light_group_[light], segments, ids(), w.divert,
            w.alt_ratio);
  }

 protected:
  const PathServices &services() const { return svc_; }
  const ElementIds &ids() const { return elements_.ids(); }
  uint32_t max_depth() const { return max_depth_; }
  const nimbus_plugin_t *light_sampler() const { return sampler_; }
  const nimbus_light_sampler_v1_t *light_sampler_iface() const { return sampler_iface_; }
  const LightSelection &light_selection() const { return selection_; }  // NEE's choice of light
  const std::vector<nimbus_light_info_t> &light_info() const { return light_info_; }
  const std::vector<uint32_t> &light_groups() const { return light_group_; }  // LightMix group per light

 private:
  Self &self() { return static_cast<Self &>(*this); }
  const Self &self() const { return static_cast<const Self &>(*this); }

  PathServices svc_;
  const nimbus_plugin_t *sampler_ = nullptr;
  const nimbus_light_sampler_v1_t *sampler_iface_ = nullptr;
  void (*record_)(const nimbus_plugin_t *, const nimbus_thread_ctx_t *, uint32_t, float) = nullptr;
  LightSelection selection_;
  uint32_t max_depth_ = 16;
  TimedScene scene_;  // at a time per camera path when something moves while the shutter is open
  const nimbus_host_spectral_v1_t *spectral_ = nullptr;  // null unless the scene disperses light
  std::vector<uint32_t> infinite_;
  std::vector<uint32_t> light_group_;  // LightMix group of each light
  std::vector<nimbus_light_info_t> light_info_;
  SampleElements elements_;
  PerWorker<Record> records_;
};

}  // namespace nimbus::sdk
