// nimbus.caustics: the one-click caustics solver (Sik & Krivanek 2019; spec in
// shared/design/caustics-solver.md). Camera paths are nimbus.pt's paths (PT + NEE + power-heuristic MIS,
// throughput Russian roulette, the same random numbers); photon passes between camera passes store
// photons after sharp bounces, and camera paths look them up at their rough vertices, with MIS
// weights that put merging and path tracing in one power-heuristic combination (mis.hpp). Without an
// active photon map a camera pass runs the plain path tracer (zero-cost rule, spec 9).
#include <nimbus/nimbus.hpp>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <string>

#include "core/bounding_sphere.hpp"
#include "core/math.hpp"
#include "core/sampling.hpp"
#include "emission_strata.hpp"
#include "emitters.hpp"
#include "mis.hpp"
#include "photon_map.hpp"
#include "sample_record.hpp"
#include "schedule.hpp"

namespace nimbus::caustics {
namespace {

const char *const kRequired[] = {
    "nimbus.host.scene-query@1", "nimbus.host.camera@1", "nimbus.host.bsdf@1",  "nimbus.host.lights@1",
    "nimbus.host.film@1",        "nimbus.host.rng@1",    "nimbus.host.tasks@1", nullptr};
const char *const kFeatures[] = {"progressive", "photon-pass", "lightmix", nullptr};

// Random-number streams: camera samples use nimbus.pt's stream (same numbers, same paths); photon path
// p of photon pass j uses derive(p, j, kStreamPhoton).
constexpr uint64_t kStreamCamera = 0;
constexpr uint64_t kStreamPhoton = 0x70686f746f6e;  // "photon"

// Photon paths per task: small enough that a pass of ~20,000 paths (the N_min floor) shares out evenly
// over the workers (4096 left one of two workers idle for up to a seventh of the pass).
constexpr uint64_t kPhotonPathsPerTask = 1024;
// A task stops tracing when its buffer holds this many photons per path (a memory guard; the caustic
// scenes store 0.3-1.05 per path). A task that stops early leaves the end of its run of emission strata
// (emission_strata.hpp) unsampled, so that region of the emitter is missing from the pass: the guard
// trades that bias for bounded memory, and only in scenes that would otherwise overflow.
constexpr uint64_t kPhotonsPerPathCap = 4;
// N_max (spec 5): photon paths per pass when every pixel is useful. Passes larger than an image's
// camera paths are spread over several iterations, so the photon : camera path ratio stays ~1.
constexpr uint64_t kMaxPhotonPaths = uint64_t(1) << 22;
constexpr uint64_t kProbePaths = uint64_t(1) << 16;
// Sharp vertices a probe task keeps for the emission target (beyond it: the box's sphere).
constexpr size_t kSharpPointsPerTask = 16384;
// Share of lookups whose radius the occupancy filter in front of the photon map covers
// (occupancy_filter.hpp).
constexpr double kFilterShare = 0.95;

inline bool has(nimbus_lobe_t lobes, nimbus_lobe_t bits) { return (lobes & bits) != 0; }

class CausticsSolver final : public sdk::Integrator {
 public:
  NIMBUS_DESCRIPTOR("nimbus.caustics", "Caustics solver (PT + selective photon merging, MIS)", "Nimbus",
                    NIMBUS_KIND_INTEGRATOR, 1, 0, 0, kFeatures, kRequired)

  nimbus_status_t init() override {
    scene_ = host().service<nimbus_host_scene_query_v1_t>(NIMBUS_SERVICE_SCENE_QUERY);
    camera_ = host().service<nimbus_host_camera_v1_t>(NIMBUS_SERVICE_CAMERA);
    bsdf_ = host().service<nimbus_host_bsdf_v1_t>(NIMBUS_SERVICE_BSDF);
    lights_ = host().service<nimbus_host_lights_v1_t>(NIMBUS_SERVICE_LIGHTS);
    film_ = host().service<nimbus_host_film_v1_t>(NIMBUS_SERVICE_FILM);
    rng_ = host().service<nimbus_host_rng_v1_t>(NIMBUS_SERVICE_RNG);
    tasks_ = host().service<nimbus_host_tasks_v1_t>(NIMBUS_SERVICE_TASKS);
    progress_ = host().service<nimbus_host_progress_v1_t>(NIMBUS_SERVICE_PROGRESS);  // optional
    lightmix_ = host().service<nimbus_ext_lightmix_v1_t>(NIMBUS_EXT_LIGHTMIX);       // optional
    return scene_ && camera_ && bsdf_ && lights_ && film_ && rng_ && tasks_ ? NIMBUS_OK
                                                                            : NIMBUS_E_UNSUPPORTED;
  }

  nimbus_status_t prepare(const nimbus_render_setup_t &setup) override {
    const nimbus_host_t *h = host().get();
    max_depth_ = setup.max_depth;
    sampler_ = setup.light_sampler;
    sampler_iface_ = setup.light_sampler_iface;
    if (!sampler_ || !sampler_iface_) return NIMBUS_E_INVALID_ARG;
    enabled_ = true;
    for (uint32_t i = 0; i < setup.option_count; ++i) {
      const nimbus_option_t &o = setup.options[i];
      if (o.key && o.value && std::strcmp(o.key, "caustics") == 0) {
        const std::string v = o.value;
        if (v == "off" || v == "false" || v == "no" || v == "0")
          enabled_ = false;
        else if (v == "on" || v == "true" || v == "yes" || v == "1")
          enabled_ = true;
        else
          return NIMBUS_E_INVALID_ARG;
      }
    }
    float center[3];
    scene_radius_ = scene_->bounding_sphere(h, center);
    scene_center_ = Vec3f::load(center);
    infinite_.clear();
    light_group_.clear();
    std::vector<Emitter> emitters;
    const uint32_t n = lights_->count(h);
    for (uint32_t i = 0; i < n; ++i) {
      nimbus_light_info_t info{};
      info.header.struct_size = sizeof(info);
      if (lights_->info(h, i, &info) != NIMBUS_OK) return NIMBUS_E_INTERNAL;
      if (info.flags & NIMBUS_LIGHT_INFINITE) infinite_.push_back(i);
      light_group_.push_back(info.group);
      emitters.push_back(make_emitter(info));
    }
    emitters_.build(std::move(emitters), scene_center_, scene_radius_);
    registered_ = {};
    registered_.direct = film_->register_element(h, "direct", 3, NIMBUS_ELEMENT_AVERAGE);
    registered_.indirect = film_->register_element(h, "indirect", 3, NIMBUS_ELEMENT_AVERAGE);
    registered_.emission = film_->register_element(h, "emission", 3, NIMBUS_ELEMENT_AVERAGE);
    registered_.albedo = film_->register_element(h, "albedo", 3, NIMBUS_ELEMENT_AVERAGE);
    registered_.normal = film_->register_element(h, "normal", 3, NIMBUS_ELEMENT_AVERAGE);
    registered_.depth = film_->register_element(h, "depth", 1, NIMBUS_ELEMENT_AVERAGE);
    registered_.caustics = film_->register_element(h, "caustics", 3, NIMBUS_ELEMENT_AVERAGE);
    registered_.caustics_merge = film_->register_element(h, "caustics_merge", 3, NIMBUS_ELEMENT_AVERAGE);
    return NIMBUS_OK;
  }

  nimbus_status_t begin_render(const nimbus_render_info_t &info) override {
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
    ids_.caustics = active(registered_.caustics);
    ids_.caustics_merge = active(registered_.caustics_merge);
    ids_.split_light = ids_.direct >= 0 || ids_.indirect >= 0 || ids_.emission >= 0 || ids_.caustics >= 0;
    ids_.lightmix = lightmix_ && lightmix_->is_active(h);
    records_.resize(info.worker_count);
    region_pixels_.resize(info.worker_count);
    for (auto &p : region_pixels_) p = 0;
    lookup_radii_.resize(info.worker_count);
    for (auto &r : lookup_radii_) r.clear();
    saw_sharp_.resize(info.worker_count);
    for (auto &s : saw_sharp_) s = 0;
    theta_pix_ = camera_->resolution(h, &width_, &height_);
    armed_ = enabled_ && emitters_.emits_photons();
    ScheduleConfig cfg;
    cfg.n_max = kMaxPhotonPaths;
    cfg.probe = kProbePaths;
    cfg.camera_paths = std::max<uint64_t>(1, uint64_t(width_) * height_);
    schedule_ = PhotonSchedule(cfg);
    useful_merge_.assign(armed_ ? size_t(width_) * height_ : 0, 0.0f);
    useful_total_.assign(useful_merge_.size(), 0.0f);
    map_ = PhotonKdTree();
    map_active_ = false;
    emitter_pdfs_known_ = false;
    next_target_ = {};
    emitters_.set_target(scene_center_, scene_radius_);
    stats_ = {};
    return NIMBUS_OK;
  }

  nimbus_status_t begin_iteration(uint64_t iteration) override {
    if (!armed_) return NIMBUS_OK;
    const uint64_t paths = schedule_.plan(iteration);
    if (paths > 0) {
      const auto t0 = std::chrono::steady_clock::now();
      if (nimbus_status_t s = photon_pass(paths); s != NIMBUS_OK) return s;
      stats_.photon_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      schedule_.pass_done(iteration, map_paths_, map_.size());
      if (schedule_.passes() == 1 && !photons_saw_sharp_ && !camera_saw_sharp()) schedule_.set_dormant(true);
    }
    map_active_ = schedule_.map_active();
    map_pass_ = schedule_.passes();
    radius_per_length_ = radius_per_length(theta_pix_, map_pass_);
    return NIMBUS_OK;
  }

  nimbus_status_t render_tile(const nimbus_thread_ctx_t &ctx, const nimbus_tile_t &tile) override {
    const nimbus_host_t *h = host().get();
    uint32_t width = 0, height = 0;
    camera_->resolution(h, &width, &height);
    SampleRecord &rec = records_[ctx];
    region_pixels_[ctx] += uint64_t(tile.x1 - tile.x0) * (tile.y1 - tile.y0);
    for (uint32_t y = tile.y0; y < tile.y1; ++y)
      for (uint32_t x = tile.x0; x < tile.x1; ++x) {
        nimbus_rng_t rng;
        rng_->derive(h, uint64_t(y) * width + x, tile.iteration, kStreamCamera, &rng);
        rec.reset();
        if (map_active_)
          trace_pixel<true>(ctx, x, y, rng, rec);
        else
          trace_pixel<false>(ctx, x, y, rng, rec);
        write(ctx, x, y, rec);
        if (armed_) {
          const size_t i = size_t(y) * width_ + x;
          useful_total_[i] += luminance(rec.beauty);
          if (map_active_) useful_merge_[i] += luminance(rec.merge);
        }
      }
    return NIMBUS_OK;
  }

  nimbus_status_t end_iteration(uint64_t iteration) override {
    if (!armed_) return NIMBUS_OK;
    // Camera paths of this iteration: the render region's pixels (tiles cover only the region).
    uint64_t pixels = 0;
    for (uint64_t &p : region_pixels_) pixels += p, p = 0;
    schedule_.set_camera_paths(pixels);
    if (schedule_.dormant() && camera_saw_sharp()) schedule_.set_dormant(false);
    if (map_active_) {
      // Useful pixels (spec 5, schedule.hpp): merges bring more than a fraction tau of the pixel's
      // light. Pixels outside the region have Mp = Tp = 0 and never count.
      uint64_t budget = 0, idle = 0;
      for (size_t i = 0; i < useful_merge_.size(); ++i) {
        budget += useful_merge_[i] > float(kBudgetThreshold) * useful_total_[i] ? 1 : 0;
        idle += useful_merge_[i] > float(kIdleThreshold) * useful_total_[i] ? 1 : 0;
      }
      const auto ratio = [&](uint64_t n) { return pixels ? std::min(1.0, double(n) / double(pixels)) : 0.0; };
      schedule_.iteration_done(iteration, {ratio(budget), ratio(idle)});
      ++stats_.map_iterations;
    }
    return NIMBUS_OK;
  }

  void end_render(nimbus_status_t) override {
    if (progress_ && enabled_) {
      const nimbus_host_t *h = host().get();
      progress_->stat_add(h, "caustics_photon_paths", double(stats_.photon_paths));
      progress_->stat_add(h, "caustics_photons", double(stats_.photons));
      progress_->stat_add(h, "caustics_photon_passes", double(stats_.passes));
      progress_->stat_add(h, "caustics_map_iterations", double(stats_.map_iterations));
      progress_->stat_add(h, "caustics_photon_seconds", stats_.photon_seconds);
      const double bytes =
          stats_.photons > 0 ? double(stats_.photon_bytes) / double(stats_.photons) : double(sizeof(Photon));
      progress_->stat_add(h, "caustics_bytes_per_photon", bytes);
    }
    map_ = PhotonKdTree();
    chunks_ = std::vector<PhotonChunk>();
    pass_photons_ = std::vector<Photon>();
  }

 private:
  static float next(nimbus_rng_t &r) { return nimbus_rng_next_float(&r); }

  // ---- vertex classification ------------------------------------------------------------------------
  // sharp: every lobe is delta or GGX alpha < kSharpAlpha (spec 2). Decided by material, not by lobe.
  bool is_sharp(const nimbus_interaction_t &ix, nimbus_lobe_t lobes) const {
    if (has(lobes, NIMBUS_LOBE_DIFFUSE)) return false;
    if (!has(lobes, NIMBUS_LOBE_GLOSSY)) return has(lobes, NIMBUS_LOBE_SPECULAR);
    return bsdf_->min_roughness(host().get(), &ix) < kSharpAlpha;
  }

  bool camera_saw_sharp() {
    for (const uint8_t s : saw_sharp_)
      if (s) return true;
    return false;
  }

  // ---- photon pass ----------------------------------------------------------------------------------
  // A cache line of its own: tasks on different workers update their chunks on every path.
  struct alignas(sdk::kCacheLineBytes) PhotonChunk {
    std::vector<Photon> photons;
    uint64_t paths = 0;  // completed paths
    bool saw_sharp = false;
    Vec3f sharp_lo{kInfinity}, sharp_hi{-kInfinity};  // bounds of the sharp vertices met
    std::vector<Vec3f> sharp_points;                  // the probe's sharp vertices (up to a cap)
    bool sharp_points_full = false;
    // Empty for the next pass, keeping the buffers' memory.
    void reset() {
      photons.clear(), sharp_points.clear();
      paths = 0, saw_sharp = false, sharp_points_full = false;
      sharp_lo = Vec3f(kInfinity), sharp_hi = Vec3f(-kInfinity);
    }
  };

  // P_pos of area lights: one sample_emission per light (uniform area sampling: constant).
  void learn_emitter_pdfs() {
    if (emitter_pdfs_known_) return;
    const auto fn = [](const nimbus_thread_ctx_t *, uint64_t b, uint64_t e, void *user) {
      auto *self = static_cast<CausticsSolver *>(user);
      for (uint64_t l = b; l < e; ++l) {
        Emitter &em = self->emitters_[l];
        if (em.kind != EmitterKind::Area) continue;
        const float u[4] = {0.5f, 0.5f, 0.25f, 0.5f};
        nimbus_light_emission_t out{};
        self->lights_->sample_emission(self->host().get(), uint32_t(l), u, &out);
        em.pdf_pos = out.pdf_pos > 0 && std::isfinite(out.pdf_pos) ? out.pdf_pos : 0.0f;
      }
    };
    tasks_->parallel_for(host().get(), emitters_.size(), 64, fn, this);
    emitter_pdfs_known_ = true;
  }

  nimbus_status_t photon_pass(uint64_t paths) {
    const nimbus_host_t *h = host().get();
    learn_emitter_pdfs();
    const uint32_t pass = schedule_.passes() + 1;
    if (next_target_.sphere.radius > 0)
      emitters_.set_target(next_target_.sphere.center, next_target_.sphere.radius, next_target_.lo,
                           next_target_.hi),
          next_target_ = {};
    const uint64_t tasks = (paths + kPhotonPathsPerTask - 1) / kPhotonPathsPerTask;
    // The task buffers, the concatenated photons and the map keep their memory from pass to pass:
    // allocated anew, their first touches (page faults) took ~40 % of the pool's map build.
    std::vector<PhotonChunk> &chunks = chunks_;
    chunks.resize(tasks);
    for (PhotonChunk &c : chunks) c.reset();
    struct Job {
      CausticsSolver *self;
      std::vector<PhotonChunk> *chunks;
      uint32_t pass;
      uint64_t paths;
    } job{this, &chunks, pass, paths};
    const auto fn = [](const nimbus_thread_ctx_t *ctx, uint64_t b, uint64_t e, void *user) {
      const Job &j = *static_cast<Job *>(user);
      PhotonChunk &c = (*j.chunks)[b / kPhotonPathsPerTask];
      c.photons.reserve(256);
      const size_t cap = size_t(e - b) * kPhotonsPerPathCap;
      for (uint64_t p = b; p < e && c.photons.size() < cap; ++p) {
        j.self->trace_photon(*ctx, p, j.paths, j.pass, c);
        ++c.paths;
      }
    };
    if (progress_) progress_->report(h, 0, paths, "photons");
    if (nimbus_status_t s = tasks_->parallel_for(h, paths, kPhotonPathsPerTask, fn, &job); s != NIMBUS_OK)
      return s;
    // Concatenate in task order: photon indices never depend on threads.
    size_t total = 0;
    uint64_t done = 0;
    bool sharp = false;
    Vec3f sharp_lo(kInfinity), sharp_hi(-kInfinity);
    for (const PhotonChunk &c : chunks) {
      total += c.photons.size(), done += c.paths, sharp |= c.saw_sharp;
      sharp_lo = min(sharp_lo, c.sharp_lo), sharp_hi = max(sharp_hi, c.sharp_hi);
    }
    // After the probe, photons aim at the bounding sphere of the sharp surfaces only (spec 6.2's
    // emission disk for infinite lights, cones for finite ones; emitters.hpp): most of a light's photons
    // would otherwise pass every caustic-forming surface. The probe's own map keeps the scene's target
    // (camera-side MIS must use the densities its photons came from), so the new target takes effect
    // with the next pass.
    // The target: the smaller of the sphere around the vertices' box and Ritter's sphere around the
    // vertices themselves (a glass sphere's hits give its own sphere, not the box's, sqrt(3) larger:
    // 3x the photons reach it), with a 5 % margin.
    if (pass == 1 && sharp) {
      Sphere target{(sharp_lo + sharp_hi) * 0.5f, 0.5f * length(sharp_hi - sharp_lo)};
      bool complete = true;
      std::vector<Vec3f> points;
      for (const PhotonChunk &c : chunks) {
        complete = complete && !c.sharp_points_full;
        points.insert(points.end(), c.sharp_points.begin(), c.sharp_points.end());
      }
      if (complete)
        if (const Sphere tight = ritter_bounding_sphere(points); tight.radius < target.radius) target = tight;
      const float radius = target.radius * 1.05f + 1e-4f * scene_radius_;
      if (radius < scene_radius_) {
        const Vec3f grow = (sharp_hi - sharp_lo) * 0.05f + Vec3f(1e-4f * scene_radius_);
        next_target_ = {{target.center, radius}, sharp_lo - grow, sharp_hi + grow};
      }
    }
    const ParallelFor parallel = [this](size_t count, const std::function<void(size_t)> &f) {
      const auto task = [](const nimbus_thread_ctx_t *, uint64_t b, uint64_t e, void *user) {
        const auto &fn = *static_cast<const std::function<void(size_t)> *>(user);
        for (uint64_t i = b; i < e; ++i) fn(size_t(i));
      };
      tasks_->parallel_for(host().get(), count, 1, task, const_cast<std::function<void(size_t)> *>(&f));
    };
    // The chunks in task order, copied concurrently.
    std::vector<Photon> &photons = pass_photons_;  // the map copies them
    photons.resize(total);
    std::vector<size_t> offset(chunks.size() + 1, 0);
    for (size_t i = 0; i < chunks.size(); ++i) offset[i + 1] = offset[i] + chunks[i].photons.size();
    parallel(chunks.size(), [&](size_t i) {
      std::copy(chunks[i].photons.begin(), chunks[i].photons.end(), photons.begin() + ptrdiff_t(offset[i]));
    });
    map_paths_ = done;
    photons_saw_sharp_ = photons_saw_sharp_ || sharp;
    // The filter's reach: the radius 95 % of the lookups since the last pass stayed within (radii
    // only shrink from pass to pass), so nearly every lookup can ask it first.
    RadiusHistogram radii;
    for (RadiusHistogram &r : lookup_radii_) radii.add(r), r.clear();
    map_.build(photons, parallel, radii.quantile(kFilterShare));
    if (progress_) progress_->report(h, paths, paths, "photons");
    stats_.photon_paths += done;
    stats_.photons += map_.size();
    stats_.photon_bytes += map_.bytes();
    ++stats_.passes;
    return NIMBUS_OK;
  }

  // One photon path: emission by power-proportional light selection, storage at rough vertices after a
  // sharp one, termination after two consecutive rough vertices (spec 4), MIS state per photon.
  void trace_photon(const nimbus_thread_ctx_t &ctx, uint64_t path, uint64_t paths, uint32_t pass,
                    PhotonChunk &out) const {
    const nimbus_host_t *h = host().get();
    nimbus_rng_t rng;
    rng_->derive(h, path, pass, kStreamPhoton, &rng);
    float sel = 0;
    const int64_t li = emitters_.pick(next(rng), &sel);
    if (li < 0 || !(sel > 0)) return;
    const uint32_t light = uint32_t(li);
    const Emitter &em = emitters_[light];
    float ue[4] = {next(rng), next(rng), next(rng), next(rng)};
    // The light's main pair of numbers (position for the sun, environment and area lights; direction
    // for point and spot lights) comes stratified along the pass (emission_strata.hpp).
    {
      const float xi = next(rng), j0 = next(rng), j1 = next(rng);
      const Vec2f s = emission_sample(path, paths, xi, j0, j1);
      const int first = em.infinite() || em.kind == EmitterKind::Area ? 0 : 2;
      ue[first] = s.x, ue[first + 1] = s.y;
    }
    nimbus_light_emission_t es;
    lights_->sample_emission(h, light, ue, &es);
    if (!(es.pdf_pos > 0) || !(es.pdf_dir > 0)) return;
    const bool delta_pos = es.flags & NIMBUS_LIGHT_DELTA_POSITION;
    const bool infinite = es.flags & NIMBUS_LIGHT_INFINITE;
    const Vec3f n_e = Vec3f::load(es.n);
    Vec3f dir0 = Vec3f::load(es.dir);
    float pdf_dir = es.pdf_dir;
    Rgb Le = Rgb::load(es.Le);
    // Infinite lights: the solver's own emission disk (emitters.hpp), same numbers as the host's.
    const Vec3f org = infinite ? emitters_.emission_origin(light, dir0, ue[0], ue[1]) : Vec3f::load(es.org);
    // Finite lights: the host's emission point, then a direction in the cone towards the target.
    if (const EmissionCone cone = infinite ? EmissionCone() : emitters_.cone(light, org); cone.active()) {
      dir0 = cone.sample(ue[2], ue[3]);
      pdf_dir = cone.pdf();
      Le = emitted(light, em, es, dir0);
    }
    const float pdf_pos = infinite ? em.pdf_pos : es.pdf_pos;
    const float cos_e = delta_pos || infinite ? 1.0f : std::abs(dot(n_e, dir0));
    const float lp = sel * pdf_pos * pdf_dir;
    Rgb beta = Le * (cos_e / lp);
    if (is_black(beta) || !is_finite(beta)) return;
    PhotonMis mis_state;
    mis_state.emit(em.hittable(), cos_e, lp);

    nimbus_ray_t ray;
    org.store(ray.org);
    dir0.store(ray.dir);
    ray.tnear = (es.flags & NIMBUS_LIGHT_AREA) ? relative_offset(org) : 0;
    ray.tfar = kInfinity;
    ray.mask = ~0u, ray.flags = 0;

    bool had_sharp = false, prev_rough = false;
    for (uint32_t depth = 1; depth <= kPhotonMaxVertices; ++depth) {
      nimbus_hit_t hit;
      scene_->intersect(h, &ctx, &ray, &hit, 1);
      if (hit.geom_id == NIMBUS_NONE) return;
      nimbus_interaction_t ix;
      scene_->interaction(h, &ray, &hit, &ix);
      const Vec3f wo = -Vec3f::load(ray.dir), ng = Vec3f::load(ix.ng);
      const float c_in = std::abs(dot(ng, wo));
      if (!(c_in > 0)) return;
      mis_state.arrive(c_in);
      const nimbus_lobe_t lobes = bsdf_->lobes(h, &ix);
      const bool rough = !is_sharp(ix, lobes);
      // A photon path that missed every sharp surface ends at its first vertex (see CameraMis: merges
      // need a sharp first photon vertex). Its only photons would come after a rough-sharp-rough
      // sequence, which path tracing samples with NEE at that first vertex, as for directions outside
      // the emission target; these paths were 18-78 % of the photon paths and their second vertex
      // 22-61 % of the traced photon vertices (docs/performance.md).
      if (rough && depth == 1) return;
      const bool smooth_only = !has(lobes, NIMBUS_LOBE_DIFFUSE | NIMBUS_LOBE_GLOSSY);
      if (!rough) {
        out.saw_sharp = true;
        out.sharp_lo = min(out.sharp_lo, Vec3f::load(ix.p));
        out.sharp_hi = max(out.sharp_hi, Vec3f::load(ix.p));
        if (pass == 1 && !out.sharp_points_full) {
          if (out.sharp_points.size() < kSharpPointsPerTask)
            out.sharp_points.push_back(Vec3f::load(ix.p));
          else
            out.sharp_points_full = true;
        }
      }

      float nee_term = 0;
      if (depth == 1 && !smooth_only) nee_term = first_vertex_nee(ix, light, em, es, wo, lp, c_in);

      // Store after a sharp bounce; a photon of depth d completes paths of >= d + 1 segments.
      const bool stored = rough && had_sharp && depth + 1 <= max_depth_;
      if (stored) {
        Photon ph;
        std::memcpy(ph.p, ix.p, sizeof(ph.p));
        ph.dir = encode_octahedral(wo);
        ph.normal = encode_octahedral(ng);
        beta.store(ph.power);
        ph.A = mis_state.A;
        ph.B = mis_state.B;
        ph.bits = Photon::pack(depth, prev_rough, mis_state.b_valid, light);
        out.photons.push_back(ph);
      }
      if (rough && prev_rough) return;  // two consecutive rough vertices
      if (depth == kPhotonMaxVertices) return;

      float wo_arr[3], u[3] = {next(rng), next(rng), next(rng)};
      wo.store(wo_arr);
      nimbus_bsdf_sample_t bs;
      bsdf_->sample(h, &ix, wo_arr, u, NIMBUS_MODE_IMPORTANCE, &bs);
      if (!(bs.pdf > 0)) return;
      const Vec3f wi = Vec3f::load(bs.wi);
      const bool delta = has(bs.lobe, NIMBUS_LOBE_SPECULAR);
      mis_state.scatter(std::abs(dot(ng, wi)), bs.pdf, bs.pdf_rev, rough, stored, delta ? 0.0f : nee_term);
      const Rgb t = Rgb::load(bs.f) * (std::abs(dot(wi, Vec3f::load(ix.ns))) / bs.pdf);
      // Russian roulette on this bounce's throughput: photon power stays roughly constant.
      const float q = std::min(1.0f, max_component(t));
      if (!(q > 0) || next(rng) >= q) return;
      beta *= t / q;
      if (is_black(beta) || !is_finite(beta)) return;
      prev_rough = rough;
      had_sharp = had_sharp || !rough;
      scene_->spawn_ray(h, &ix, bs.wi, kInfinity, &ray);
    }
  }

  // The emitter surface point a photon of area light `light` left from, as an interaction.
  static nimbus_interaction_t emission_point(uint32_t light, const nimbus_light_emission_t &es) {
    nimbus_interaction_t on_light{};
    std::memcpy(on_light.p, es.org, sizeof(on_light.p));
    std::memcpy(on_light.ng, es.n, sizeof(on_light.ng));
    std::memcpy(on_light.ns, es.n, sizeof(on_light.ns));
    on_light.light_id = light;
    on_light.flags = NIMBUS_IX_EMISSIVE;
    return on_light;
  }

  // Radiance (area) or intensity (point, spot) that finite light `light` emits from es.org along w.
  Rgb emitted(uint32_t light, const Emitter &em, const nimbus_light_emission_t &es, const Vec3f &w) const {
    const nimbus_host_t *h = host().get();
    if (em.kind == EmitterKind::Point) return Rgb::load(es.Le);  // isotropic
    if (em.kind == EmitterKind::Spot) {
      // The spot's falloff towards w: its intensity / d^2 as seen from a receiver at unit distance.
      nimbus_interaction_t at{};
      (Vec3f::load(es.org) + w).store(at.p);
      const float u[2] = {0.5f, 0.5f};
      nimbus_light_incident_t li{};
      lights_->sample_incident(h, light, &at, u, &li);
      return li.pdf > 0 ? Rgb::load(li.L) * length_squared(Vec3f::load(at.p) - Vec3f::load(es.org)) : Rgb(0);
    }
    const nimbus_interaction_t on_light = emission_point(light, es);
    float wo[3], L[3];
    w.store(wo);
    lights_->eval_emitted(h, &on_light, wo, L);
    return Rgb::load(L);
  }

  // E of the first photon vertex: how NEE from it would have sampled the emission point.
  float first_vertex_nee(const nimbus_interaction_t &ix, uint32_t light, const Emitter &em,
                         const nimbus_light_emission_t &es, const Vec3f &wo, float lp, float c_in) const {
    const nimbus_host_t *h = host().get();
    const float pmf = sampler_iface_->pmf(sampler_, &ix, light);
    if (!(pmf > 0)) return 0;
    float wo_arr[3];
    wo.store(wo_arr);
    if (em.delta_position()) {
      const float d2 = length_squared(Vec3f::load(es.org) - Vec3f::load(ix.p));  // point and spot
      return photon_nee_term(true, pmf, d2, lp, c_in);
    }
    if (em.infinite()) {
      const float pdf = em.delta_direction() ? 1.0f : lights_->pdf_incident(h, light, &ix, wo_arr, nullptr);
      return photon_nee_term(true, pmf * pdf, 1.0f, lp, c_in);
    }
    const nimbus_interaction_t on_light = emission_point(light, es);
    const float pdf = lights_->pdf_incident(h, light, &ix, wo_arr, &on_light);
    const float cos_z = std::abs(dot(Vec3f::load(es.n), wo));  // wo = -(the photon's direction)
    // nk * d2 = pmf * pdf * cos_z: pass d2 = 1 with nk already multiplied out.
    return photon_nee_term(true, pmf * pdf * cos_z, 1.0f, lp, c_in);
  }

  // ---- camera paths ---------------------------------------------------------------------------------
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
    put(ids_.caustics, rec.caustics);
    put(ids_.caustics_merge, rec.merge);
    put(ids_.albedo, rec.albedo);
    put(ids_.normal, rec.normal);
    if (ids_.depth >= 0) film_->accumulate(h, &ctx, ids_.depth, x, y, &rec.depth);
    for (const auto &[g, v] : rec.groups) {
      float a[3];
      v.store(a);
      lightmix_->accumulate(h, &ctx, g, x, y, a);
    }
  }

  // Camera-side MIS state of one path (only with an active photon map).
  struct CameraState {
    CameraMis mis;
    float radius = 0;  // r_a: fixed at the first rough vertex (spec 3.5)
    float r = 0;       // r_s of the current lookup vertex: r_a * kRadiusGrowth^(c_s - 1)
    float length = 0;  // path length from the lens to the current vertex
  };

  // nimbus.pt's camera path. With Map, the same path (same random numbers) also carries the MIS state,
  // looks photons up at its rough vertices and weights hits and NEE against merging.
  template <bool Map>
  void trace_pixel(const nimbus_thread_ctx_t &ctx, uint32_t x, uint32_t y, nimbus_rng_t &rng,
                   SampleRecord &rec) const {
    const nimbus_host_t *h = host().get();
    nimbus_camera_sample_t cs{{0, 0}, {0, 0}};
    float filter_weight = 1;
    if (has_sample_film()) {
      const float uf[2] = {next(rng), next(rng)};
      cs.lens[0] = next(rng), cs.lens[1] = next(rng);
      filter_weight = camera_->sample_film(h, x, y, uf, cs.film);
    } else {
      cs.film[0] = float(x) + next(rng), cs.film[1] = float(y) + next(rng);
      cs.lens[0] = next(rng), cs.lens[1] = next(rng);
    }
    nimbus_ray_t ray;
    const float cam_weight = camera_->generate_ray(h, &cs, &ray) * filter_weight;
    if (has_sample_film() ? cam_weight == 0 : cam_weight <= 0) return;

    Rgb beta(cam_weight);
    bool specular = true;  // the previous bounce was delta (or there was none): no MIS on hits
    // The albedo element takes the first non-specular surface; no host call when nobody asked for it.
    bool albedo_done = ids_.albedo < 0;
    float prev_pdf = 0;           // solid-angle pdf of the BSDF sample that produced `ray`
    nimbus_interaction_t prev{};  // the vertex `ray` left
    CameraState cam;
    // `segments` counts the segments of the path up to the vertex `ray` reaches.
    for (uint32_t segments = 1;; ++segments) {
      nimbus_hit_t hit;
      scene_->intersect(h, &ctx, &ray, &hit, 1);
      const Vec3f dir = Vec3f::load(ray.dir);
      if (hit.geom_id == NIMBUS_NONE) {
        add_infinite<Map>(rec, beta, prev, dir, specular, prev_pdf, segments, cam);
        break;
      }
      nimbus_interaction_t ix;
      scene_->interaction(h, &ray, &hit, &ix);
      const Vec3f wo = -dir;
      if (segments == 1) {
        rec.normal = Vec3f::load(ix.ns);
        rec.depth = hit.t;
      }
      if constexpr (Map) {
        cam.length += hit.t;
        cam.mis.arrive(std::abs(dot(Vec3f::load(ix.ng), dir)));
      }

      if (ix.flags & NIMBUS_IX_EMISSIVE) {
        float le[3], wo_arr[3];
        wo.store(wo_arr);
        lights_->eval_emitted(h, &ix, wo_arr, le);
        const Rgb Le = Rgb::load(le);
        if (!is_black(Le)) {
          const uint32_t l = ix.light_id;
          if constexpr (!Map) {
            float w = 1;
            if (!specular) {
              const float light_pdf =
                  sampler_iface_->pmf(sampler_, &prev, l) * lights_->pdf_incident(h, l, &prev, ray.dir, &ix);
              w = power_heuristic(prev_pdf, light_pdf);
            }
            rec.add(beta * Le * w, light_group_[l], segments, ids_);
          } else {
            float nee_ratio = 0;
            if (!specular) {
              const float light_pdf =
                  sampler_iface_->pmf(sampler_, &prev, l) * lights_->pdf_incident(h, l, &prev, ray.dir, &ix);
              nee_ratio = mis(light_pdf / prev_pdf);
            }
            const float lp = emitters_.lp(l, Vec3f::load(ix.p), Vec3f::load(ix.ng), wo, Vec3f::load(prev.p));
            const float w = hit_weight(nee_ratio, cam.mis.s_cam(segments), lp);
            rec.add(beta * Le * w, light_group_[l], segments, ids_, lp > 0 && cam.mis.eligible(segments));
          }
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
      bool lookup = false;
      if constexpr (Map) {
        const bool rough = !is_sharp(ix, lobes);
        lookup = cam.mis.append(rough);
        if (lookup) {
          if (cam.mis.rough_count == 1)
            cam.radius = merge_radius(radius_per_length_, cam.length, scene_radius_);
          cam.r = cam.mis.rough_count == 1 ? cam.radius : cam.r * kRadiusGrowth;
        }
        // A photon has at least 2 vertices (a sharp one and x_s): paths of >= segments + 2 segments.
        if (lookup && segments + 2 <= max_depth_) {
          lookup_radii_[ctx].add(cam.r);
          merge(ix, wo, beta, cam, segments, rec);
        }
      } else if (!saw_sharp_[ctx.worker_index] && has(lobes, NIMBUS_LOBE_SPECULAR | NIMBUS_LOBE_GLOSSY) &&
                 is_sharp(ix, lobes)) {
        saw_sharp_[ctx.worker_index] = 1;  // wakes a dormant solver (zero-cost rule)
      }
      if (segments >= max_depth_) break;

      if (!smooth_only) direct_light<Map>(ctx, ix, wo, rng, beta, segments + 1, rec, cam);

      // Continue the path by sampling the BSDF.
      float wo_arr[3], u[3] = {next(rng), next(rng), next(rng)};
      wo.store(wo_arr);
      nimbus_bsdf_sample_t bs;
      bsdf_->sample(h, &ix, wo_arr, u, NIMBUS_MODE_RADIANCE, &bs);
      if (!(bs.pdf > 0)) break;
      const Vec3f wi = Vec3f::load(bs.wi);
      if constexpr (Map)
        cam.mis.scatter(std::abs(dot(Vec3f::load(ix.ng), wi)), bs.pdf, bs.pdf_rev, lookup, segments,
                        kPi * cam.r * cam.r * float(map_paths_));
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

  // Radiance from infinite lights along an escaped ray, MIS-weighted against light sampling (and, with
  // a map, against merging).
  template <bool Map>
  void add_infinite(SampleRecord &rec, const Rgb &beta, const nimbus_interaction_t &prev, const Vec3f &dir,
                    bool specular, float prev_pdf, uint32_t segments, const CameraState &cam) const {
    float d[3];
    dir.store(d);
    for (uint32_t l : infinite_) {
      float le[3];
      lights_->eval_infinite(host().get(), l, d, le);
      const Rgb Le = Rgb::load(le);
      if (is_black(Le)) continue;
      if constexpr (!Map) {
        float w = 1;
        if (!specular) {
          const float light_pdf = sampler_iface_->pmf(sampler_, &prev, l) *
                                  lights_->pdf_incident(host().get(), l, &prev, d, nullptr);
          w = power_heuristic(prev_pdf, light_pdf);
        }
        rec.add(beta * Le * w, light_group_[l], segments, ids_);
      } else {
        float nee_ratio = 0;
        if (!specular) {
          const float light_pdf = sampler_iface_->pmf(sampler_, &prev, l) *
                                  lights_->pdf_incident(host().get(), l, &prev, d, nullptr);
          nee_ratio = mis(light_pdf / prev_pdf);
        }
        const float lp = emitters_.lp(l, Vec3f(), Vec3f(), -dir, Vec3f::load(prev.p));
        const float w = hit_weight(nee_ratio, cam.mis.s_cam(segments), lp);
        rec.add(beta * Le * w, light_group_[l], segments, ids_, lp > 0 && cam.mis.eligible(segments));
      }
    }
  }

  // Next-event estimation: one light chosen by the light sampler, MIS-weighted against BSDF sampling
  // (and, with a map, against merging). `segments` = length of the path it completes.
  template <bool Map>
  void direct_light(const nimbus_thread_ctx_t &ctx, const nimbus_interaction_t &ix, const Vec3f &wo,
                    nimbus_rng_t &rng, const Rgb &beta, uint32_t segments, SampleRecord &rec,
                    const CameraState &cam) const {
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
    float wo_arr[3], f[3], bsdf_pdf = 0, bsdf_pdf_rev = 0;
    wo.store(wo_arr);
    bsdf_->eval(h, &ix, wo_arr, ls.wi, NIMBUS_MODE_RADIANCE, f, &bsdf_pdf, Map ? &bsdf_pdf_rev : nullptr);
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
    if constexpr (!Map) {
      const float w = delta ? 1.0f : power_heuristic(light_pdf, bsdf_pdf);
      rec.add(beta * contrib * Li * (w / light_pdf), light_group_[light], segments, ids_);
    } else {
      const Emitter &em = emitters_[light];
      const bool infinite = ls.flags & NIMBUS_LIGHT_INFINITE;
      const float hit_ratio = delta ? 0.0f : mis(bsdf_pdf / light_pdf);
      const float lp = emitters_.lp(light, Vec3f::load(ls.p), Vec3f::load(ls.n), -wi, Vec3f::load(ix.p));
      const float cos_j = std::abs(dot(Vec3f::load(ix.ng), wi));
      const float d2 = infinite ? 1.0f : ls.dist * ls.dist;
      float nk = pmf;  // delta lights
      if (!delta) nk = infinite ? light_pdf : light_pdf * std::abs(dot(Vec3f::load(ls.n), wi)) / d2;
      (void)em;
      const float w = nee_weight(hit_ratio, bsdf_pdf_rev, cam.mis.s_cam(segments), lp, cos_j / d2, nk);
      rec.add(beta * contrib * Li * (w / light_pdf), light_group_[light], segments, ids_,
              lp > 0 && cam.mis.eligible(segments));
    }
  }

  // Photon lookup at the lookup vertex x_s (spec 3.4): Epanechnikov kernel, MIS-weighted merges.
  __attribute__((noinline)) void merge(const nimbus_interaction_t &ix, const Vec3f &wo, const Rgb &beta,
                                       const CameraState &cam, uint32_t s, SampleRecord &rec) const {
    const nimbus_host_t *h = host().get();
    const float r = cam.r, r2 = r * r;
    const float neff = float(map_paths_);
    const float inv_paths = 1.0f / neff;
    const float m_neff = mis(neff), eta = mis(kPi * r2 * neff);
    const Vec3f ng = Vec3f::load(ix.ng);
    float wo_arr[3];
    wo.store(wo_arr);
    const float kernel_norm = 2 / (kPi * r2);
    // Photons on the same flat surface carry the same quantised normal: skip decoding those. Encoded at
    // the first photon found: most lookups find none (query() turns them away first).
    uint32_t ng_code = 0;
    bool ng_encoded = false;
    Rgb sum(0);  // without LightMix, one record entry per lookup
    map_.query(Vec3f::load(ix.p), r, [&](const PhotonData &ph, float d2) {
      const uint32_t k = s + ph.depth();
      if (k > max_depth_) return;
      if (!ng_encoded) ng_code = encode_octahedral(ng), ng_encoded = true;
      if (ph.normal != ng_code && !(dot(decode_octahedral(ph.normal), ng) > 0)) return;
      const Vec3f wp = decode_octahedral(ph.dir);
      float wp_arr[3], f[3], pdf_fwd = 0, pdf_rev = 0;
      wp.store(wp_arr);
      bsdf_->eval(h, &ix, wo_arr, wp_arr, NIMBUS_MODE_RADIANCE, f, &pdf_fwd, &pdf_rev);
      const Rgb fr = Rgb::load(f);
      if (is_black(fr)) return;
      const float w = merge_weight(ph.A, ph.B, ph.b_valid(), ph.prev_rough(), pdf_fwd, pdf_rev, eta, m_neff,
                                   m_neff, cam.mis.gamma_sum(k));
      const float kernel = kernel_norm * (1 - d2 / r2);
      const Rgb c = fr * Rgb::load(ph.power) * (w * kernel);
      if (!is_finite(c) || is_black(c)) return;
      if (ids_.lightmix)
        rec.add_merge(beta * c * inv_paths, light_group_[ph.light()], ids_);
      else
        sum += c;
    });
    if (!ids_.lightmix && !is_black(sum)) rec.add_merge(beta * sum * inv_paths, 0, ids_);
  }

  bool has_sample_film() const { return NIMBUS_HAS_MEMBER(camera_, nimbus_host_camera_v1_t, sample_film); }

  const nimbus_host_scene_query_v1_t *scene_ = nullptr;
  const nimbus_host_camera_v1_t *camera_ = nullptr;
  const nimbus_host_bsdf_v1_t *bsdf_ = nullptr;
  const nimbus_host_lights_v1_t *lights_ = nullptr;
  const nimbus_host_film_v1_t *film_ = nullptr;
  const nimbus_host_rng_v1_t *rng_ = nullptr;
  const nimbus_host_tasks_v1_t *tasks_ = nullptr;
  const nimbus_host_progress_v1_t *progress_ = nullptr;
  const nimbus_plugin_t *sampler_ = nullptr;
  const nimbus_light_sampler_v1_t *sampler_iface_ = nullptr;
  const nimbus_ext_lightmix_v1_t *lightmix_ = nullptr;
  uint32_t max_depth_ = 16;
  std::vector<uint32_t> infinite_;
  std::vector<uint32_t> light_group_;  // LightMix group of each light
  ElementIds registered_, ids_;        // all registered elements; the active ones
  sdk::PerWorker<SampleRecord> records_;
  mutable sdk::PerWorker<uint8_t> saw_sharp_;             // a camera path met a sharp vertex (per worker)
  mutable sdk::PerWorker<RadiusHistogram> lookup_radii_;  // radii of the lookups since the last photon pass

  // The solver.
  bool enabled_ = true;  // the `caustics` switch
  bool armed_ = false;   // enabled and some light emits photons
  EmitterSet emitters_;
  bool emitter_pdfs_known_ = false;
  float scene_radius_ = 1, theta_pix_ = 0;
  Vec3f scene_center_;
  struct Target {
    Sphere sphere;
    Vec3f lo{kInfinity}, hi{-kInfinity};  // the box around its sharp vertices (the sun's rectangle)
  } next_target_;                         // emission target (emitters.hpp) from the next photon pass on
  uint32_t width_ = 0, height_ = 0;
  PhotonSchedule schedule_;
  PhotonKdTree map_;
  std::vector<PhotonChunk> chunks_;   // photon pass: one buffer per task
  std::vector<Photon> pass_photons_;  // photon pass: the tasks' photons in task order
  uint64_t map_paths_ = 0;            // photon paths behind the current map (Neff)
  uint32_t map_pass_ = 0;             // its photon pass index j
  float radius_per_length_ = 0;       // merge radius per unit path length at pass j
  bool map_active_ = false;
  bool photons_saw_sharp_ = false;
  std::vector<float> useful_merge_, useful_total_;  // per pixel: accumulated lum of merges (Mp), beauty (Tp)
  sdk::PerWorker<uint64_t> region_pixels_;          // pixels rendered this iteration (per worker)
  struct Stats {
    uint64_t photon_paths = 0, photons = 0, photon_bytes = 0, passes = 0, map_iterations = 0;
    double photon_seconds = 0;  // photon tracing and kd-tree builds
  } stats_;
};

}  // namespace
}  // namespace nimbus::caustics

NIMBUS_PLUGIN_LIBRARY(nimbus::caustics::CausticsSolver)
