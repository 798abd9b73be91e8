// nimbus.caustics: the one-click caustics solver (Sik & Krivanek 2019; spec in
// shared/design/caustics-solver.md). Camera paths are nimbus.pt's paths (the SDK's camera-path layer,
// same random numbers); photon passes between camera passes store photons after sharp bounces
// (photon_pass, photon_tracer), camera paths look them up at their rough vertices, and photons the lens
// sees are splatted (photon_splats), with MIS weights that put merging, splatting and path tracing in
// one power-heuristic combination (merging, mis.hpp). Without an active photon map a camera pass runs
// the plain path tracer (zero-cost rule, spec 9). This file holds the solver's state and its hooks; the
// schedule (schedule.hpp) decides when and how many photons.
#include <nimbus/nimbus.hpp>

#include <chrono>
#include <utility>

#include <nimbus/cpp/camera_path.hpp>
#include <nimbus/cpp/render_state.hpp>
#include <nimbus/cpp/task_split.hpp>

#include "caustics_record.hpp"
#include "emission_selection.hpp"
#include "emitters.hpp"
#include "iteration_inputs.hpp"
#include "lens_connections.hpp"
#include "lookup_roulette.hpp"
#include "merging.hpp"
#include "photon_budget.hpp"
#include "photon_pass.hpp"
#include "photon_splats.hpp"
#include "schedule.hpp"
#include "solver_options.hpp"
#include "solver_stats.hpp"
#include "useful_pixels.hpp"

namespace nimbus::caustics {
namespace {

class CausticsSolver final : public sdk::CameraPathIntegrator<CausticsSolver, CausticsRecord> {
  using Base = sdk::CameraPathIntegrator<CausticsSolver, CausticsRecord>;

 public:
  NIMBUS_DESCRIPTOR_WITH_OPTIONS("nimbus.caustics", "Caustics solver (PT + selective photon merging, MIS)",
                                 "Nimbus", NIMBUS_KIND_INTEGRATOR, 1, 0, 0, kFeatures, kRequired, kOptions)

  const void *interface(const char *id, uint32_t rev) override {
    if (const void *t = sdk::render_state_interface<CausticsSolver>(id, rev)) return t;
    return Base::interface(id, rev);
  }

  nimbus_status_t init() override {
    if (nimbus_status_t s = Base::init(); s != NIMBUS_OK) return s;
    tasks_ = host().service<nimbus_host_tasks_v1_t>(NIMBUS_SERVICE_TASKS);
    progress_ = host().service<nimbus_host_progress_v1_t>(NIMBUS_SERVICE_PROGRESS);  // optional
    // Photon emission and the camera side's emission densities come from the lights service (SDK 1.2).
    if (!NIMBUS_HAS_MEMBER(services().lights, nimbus_host_lights_v1_t, pdf_emission)) {
      log(NIMBUS_LOG_ERROR, "needs a host whose lights service has eval_emission and pdf_emission (SDK 1.2)");
      return NIMBUS_E_UNSUPPORTED;
    }
    return tasks_ ? NIMBUS_OK : NIMBUS_E_UNSUPPORTED;
  }

  nimbus_status_t prepare(const nimbus_render_setup_t &setup) override {
    options_ = SolverOptions::of(setup);
    budget_ = PhotonBudget(options_.photon_memory_mb);
    if (nimbus_status_t s = Base::prepare(setup); s != NIMBUS_OK) return s;
    seed_ = setup.seed;
    guide_ = options_.uniform_emission ? GuideBinding{} : GuideBinding::of(setup.guide);
    if (setup.guide && !options_.uniform_emission && !guide_)
      log(NIMBUS_LOG_WARNING, "the bound guide has no nimbus.iface.guiding@2: photons are not guided");
    float center[3];
    scene_radius_ = services().scene->bounding_sphere(host().get(), center);
    scene_center_ = Vec3f::load(center);
    std::vector<Emitter> emitters;
    for (const nimbus_light_info_t &info : light_info()) emitters.push_back(make_emitter(info));
    // Photons aim at every object that can form a caustic, known before the first pass (spec 6.2).
    emitters_.build(std::move(emitters), scene_center_, scene_radius_, host().get(), services().lights,
                    query_sharp_targets(host().get(), services().scene, kSharpAlpha));
    merge_element_ =
        services().film->register_element(host().get(), "caustics_merge", 3, NIMBUS_ELEMENT_AVERAGE);
    LensConnections::register_elements(services().film, host().get(), diverted_element());
    return NIMBUS_OK;
  }

  const char *diverted_element() const { return "caustics"; }

  nimbus_status_t begin_render(const nimbus_render_info_t &info) override {
    const nimbus_host_t *h = host().get();
    if (nimbus_status_t s = Base::begin_render(info); s != NIMBUS_OK) return s;
    split_ = sdk::TaskSplit::of(info);
    merge_id_ = services().film->is_active(h, merge_element_) ? merge_element_ : NIMBUS_ELEMENT_INVALID;
    region_pixels_.resize(info.worker_count), lookup_radii_.resize(info.worker_count);
    tallies_.resize(info.worker_count), marks_.resize(info.worker_count);
    importance_ = pass_importance_ = ImportanceMap(scene_center_, scene_radius_);
    theta_pix_ = services().camera->resolution(h, &width_, &height_);
    merge_.clock = PhotonClock::of(h, services().camera, options_.times_matched);
    merge_.spectral = spectral();
    // Zero-cost rule (spec 9): no sharp object or no photon-emitting light, no photon pass at all.
    const bool caustics_can_form = emitters_.emits_photons() && !emitters_.targets().empty();
    // Light selection (spec 6.1): the prior from where the camera is, adapted at every photon pass.
    nimbus_camera_sample_t centre{{0.5f * float(width_), 0.5f * float(height_)}, {0.5f, 0.5f}};
    nimbus_ray_t eye{};
    services().camera->generate_ray(h, &centre, &eye);
    EmissionSelection::Inputs selection{emitters_.photon_powers(), Vec3f::load(eye.org), scene_radius_,
                                        ids().lightmix, options_.power_selection};
    nimbus_status_t s = emission_selection_.configure(light_sampler(), light_sampler_iface(), h,
                                                      services().lights, std::move(selection));
    if (s != NIMBUS_OK || (s = select_lights()) != NIMBUS_OK) return s;
    emitters_.reset_emission_map(options_.adaptive_map);
    pending_used_.clear();
    armed_ = options_.enabled && caustics_can_form;
    // No splats for lookups that ignore photon times (a measurement option): merges then mix times.
    lens_.begin_render(emitters_,
                       armed_ && options_.times_matched && splats_possible(h, services(), spectral()),
                       normalize(Vec3f::load(eye.dir)), theta_pix_, uint64_t(width_) * height_, merge_);
    // The `caustics` element is the light of a class of paths (spec 8), with or without a map, and with
    // the switch off too (then the path tracer's share of that light).
    classify_ = caustics_can_form && ids().diverted != NIMBUS_ELEMENT_INVALID;
    ScheduleConfig cfg;
    cfg.camera_paths = cfg.frame_pixels = std::max<uint64_t>(1, uint64_t(width_) * height_);
    schedule_ = PhotonSchedule(cfg);
    const size_t pixels = armed_ ? size_t(width_) * height_ : 0;
    useful_.reset(pixels), pixel_radius_.reset(pixels);
    pass_.release();
    map_active_ = rebuild_map_ = false;
    map_request_ = 0, map_reach_ = 0, photon_work_ = 0;
    roulette_ = {}, stats_ = {};
    return NIMBUS_OK;
  }

  nimbus_status_t begin_iteration(uint64_t frame_iteration) override {
    if (!armed_) return NIMBUS_OK;
    const uint64_t iteration = split_.task_number(frame_iteration);
    std::string warning;  // the pass's paths, fewer if its photons could exceed the memory budget
    const uint64_t paths = budget_.paths_for_pass(schedule_.plan(iteration), pass_.map(), warning);
    if (!warning.empty()) log(NIMBUS_LOG_WARNING, warning);
    if (rebuild_map_) {
      // A resumed render: the map of the last pass, from the same arguments (photon_pass is deterministic)
      // and the same light selection, with the lookups' flags on its paths as they were saved. Traced
      // even when a new pass is due now: the new pass's light selection and guiding count its paths.
      if (nimbus_status_t s = select_lights(); s != NIMBUS_OK) return s;
      PhotonPass::Result result;
      if (nimbus_status_t s = photon_pass(schedule_.passes(), map_request_, map_reach_, result);
          s != NIMBUS_OK)
        return s;
      if (!pass_.path_use().set_used_bits(pending_used_)) return NIMBUS_E_INVALID_ARG;
    }
    rebuild_map_ = false;
    pending_used_.clear();
    if (paths > 0) {
      const auto t0 = std::chrono::steady_clock::now();
      // The last map's uniform paths and whether lookups used them adapt the light selection (spec 6.1)
      // and the emission map's densities (photon_emission: adaptive-map).
      EmissionMap &map = emitters_.emission_map();
      pass_.path_use().for_each([&](uint32_t light, uint32_t cell, bool uniform, bool used) {
        if (uniform) emission_selection_.count(light, used), map.count(cell, used);
        stats_.used_paths += used ? 1 : 0;
      });
      if (nimbus_status_t s = select_lights(); s != NIMBUS_OK) return s;
      map.update();
      map_request_ = paths, map_reach_ = PhotonPass::filter_reach(lookup_radii_);
      PhotonPass::Result result;
      if (nimbus_status_t s = photon_pass(schedule_.passes() + 1, paths, map_reach_, result); s != NIMBUS_OK)
        return s;
      stats_.pass_done(result, pass_.map(),
                       std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
      stats_.splats += pass_.splats().size();
      useful_.map_changed(!result.guided, sdk::host_parallel_for(tasks_, host().get()));
      schedule_.pass_done(iteration, result.traced, pass_.map().size());
    }
    map_active_ = schedule_.map_active();
    const uint32_t pass = uint32_t(split_.frame_number(schedule_.passes()));
    merge_.radius_per_length = radius_per_length(theta_pix_, pass);
    merge_.time_half_width = PhotonClock::half_width(pass);
    merge_.lambda_half_width = PhotonClock::lambda_half_width(pass);
    merge_.lookup_probability = roulette_.probabilities();
    return lens_.camera_pass(
        map_active_,
        {host().get(), tasks_, services().film, ids().lightmix ? services().lightmix : nullptr, &merge_,
         &pixel_radius_, &useful_, width_, height_, pass_.splats(), pass_.photons()},
        tracer(), frame_iteration, merge_, stats_);
  }

  // The camera-path layer's hooks: the camera path of one sample, and the statistics of the schedule.
  void sample(const nimbus_thread_ctx_t &ctx, uint32_t x, uint32_t y, nimbus_rng_t &rng,
              CausticsRecord &rec) {
    const size_t pixel = size_t(y) * width_ + x;
    // The pixel's statistics, touched when its path ends and long out of cache, load while it is traced.
    if (armed_) useful_.prefetch(pixel), pixel_radius_.prefetch(pixel);
    if (map_active_) {
      MergingPath path(merge_, lookup_radii_[ctx], tallies_[ctx], guide_ ? &marks_[ctx] : nullptr,
                       importance_, mix64(rng.state ^ rng.inc), pixel_radius_, pixel);
      trace(ctx, x, y, rng, rec, path);
    } else if (classify_) {
      ClassifyingPath path(emitters_, services().bsdf, host().get());
      trace(ctx, x, y, rng, rec, path);
    } else {
      sdk::PlainPath path;
      trace(ctx, x, y, rng, rec, path);
    }
  }
  void tile_begins(const nimbus_thread_ctx_t &ctx, const nimbus_tile_t &tile) {
    region_pixels_[ctx] += uint64_t(tile.x1 - tile.x0) * (tile.y1 - tile.y0);
  }
  void sample_done(const nimbus_thread_ctx_t &ctx, uint32_t x, uint32_t y, const CausticsRecord &rec) {
    if (merge_id_ >= 0) {
      float a[3];
      rec.merge.store(a);
      services().film->accumulate(host().get(), &ctx, merge_id_, x, y, a);
    }
    const size_t i = size_t(y) * width_ + x;
    if (armed_) useful_.add(i, rec), lens_.add_sample(i, rec);
  }

  nimbus_status_t end_iteration(uint64_t frame_iteration) override {
    if (!armed_) return NIMBUS_OK;
    const uint64_t iteration = split_.task_number(frame_iteration);
    for (ImportanceMarks &m : marks_) importance_.merge(m);
    // Camera paths of this iteration: the render region's pixels (tiles cover only the region).
    uint64_t pixels = 0;
    for (uint64_t &p : region_pixels_) pixels += p, p = 0;
    schedule_.set_camera_paths(pixels);
    const uint64_t light_path_work = lens_.iteration_done(pixels);
    const UsefulPixels::Summary summary = useful_.summarize(pixels, schedule_.iterations_per_map(),
                                                            sdk::host_parallel_for(tasks_, host().get()));
    if (map_active_) {
      // Light paths are camera-pass work.
      const CameraTally sum = sum_tallies(tallies_, [&](const CameraTally &t) { stats_.camera_done(t); });
      const IterationInputs in =
          iteration_inputs(summary, sum, light_path_work, pixels, schedule_.map_photon_ratio(), photon_work_);
      roulette_.update(in.roulette);
      lens_.pass_done(in.work());
      schedule_.iteration_done(iteration, summary.useful, in.efficiency);
      pixel_radius_.end_iteration();
      ++stats_.map_iterations;
    }
    return NIMBUS_OK;
  }

  void end_render(nimbus_status_t) override {
    if (progress_ && options_.enabled)
      stats_.report(progress_, host().get(),
                    {schedule_.photon_ratio(), roulette_.probability(kFirstLookup),
                     roulette_.probability(kLaterLookup), double(importance_.cells()), double(sizeof(Photon)),
                     double(emitters_.emission_map().slots_learnt())}),
          lens_.report(progress_, host().get());
    pass_.release();
  }

  // The render's learnt state (nimbus/render_state.h): the schedule, the per-pixel statistics, what the
  // current map was traced with (it is traced again on resume rather than stored) and the statistics.
  nimbus_status_t save_state(uint64_t, sdk::StateWriter &w) {
    w.put(kStateVersion), w.put(uint8_t(armed_));
    if (!armed_) return NIMBUS_OK;
    schedule_.save(w);
    w.put(photon_work_), w.put(map_request_), w.put(map_reach_);
    RadiusHistogram radii;
    for (RadiusHistogram &r : lookup_radii_) radii.add(r);
    w.put_array(std::as_const(radii).counts());
    useful_.save(w), pixel_radius_.save(w);
    roulette_.save(w);
    importance_.save(w), pass_importance_.save(w);
    emission_selection_.save(w);
    emitters_.emission_map().save(w), lens_.trial().save(w);
    pass_.path_use().save_used(w);
    w.put(stats_);
    return NIMBUS_OK;
  }
  nimbus_status_t restore_state(uint64_t, sdk::StateReader &r) {
    uint32_t version = 0;
    uint8_t armed = 0;
    if (!r.get(version) || version != kStateVersion) return NIMBUS_E_VERSION;
    if (!r.get(armed) || bool(armed) != armed_) return NIMBUS_E_INVALID_ARG;
    if (!armed_) return r.done() ? NIMBUS_OK : NIMBUS_E_INVALID_ARG;
    // Read into copies; the solver changes only once everything has been read.
    PhotonSchedule schedule;
    double work = 0;
    uint64_t request = 0;
    float reach = 0;
    RadiusHistogram radii;
    UsefulPixels useful = useful_;
    PixelRadius pixel_radius = pixel_radius_;
    LookupRoulette roulette;
    ImportanceMap importance = importance_, pass_importance = pass_importance_;
    EmissionSelection selection = emission_selection_;
    EmissionMap emission_map = emitters_.emission_map();
    LightPathTrial trial = lens_.trial();
    std::vector<uint64_t> used;
    SolverStats stats;
    if (!(schedule.restore(r) && r.get(work) && r.get(request) && r.get(reach) &&
          r.get_array(radii.counts()) && useful.restore(r) && pixel_radius.restore(r) &&
          roulette.restore(r) && importance.restore(r) && pass_importance.restore(r) &&
          selection.restore(r) && emission_map.restore(r) && trial.restore(r) &&
          PathUse::read_used(r, used) && r.get(stats) && r.done()))
      return NIMBUS_E_INVALID_ARG;
    emission_selection_ = std::move(selection), pending_used_ = std::move(used);
    emitters_.emission_map() = std::move(emission_map), lens_.trial() = std::move(trial);
    emitters_.emission_map().update();  // the densities the current map was traced with
    schedule_ = schedule, photon_work_ = work, map_request_ = request, map_reach_ = reach;
    roulette_ = roulette, importance_ = std::move(importance), pass_importance_ = std::move(pass_importance);
    for (RadiusHistogram &h : lookup_radii_) h.clear();
    if (lookup_radii_.size() > 0) lookup_radii_[0u].add(radii);
    useful_ = std::move(useful), pixel_radius_ = std::move(pixel_radius), stats_ = stats;
    rebuild_map_ = schedule_.map_active() && schedule_.passes() > 0;
    return NIMBUS_OK;
  }

 private:
  // The light selection of the next photon map, from the bound sampler (emission_selection.hpp).
  nimbus_status_t select_lights() {
    std::vector<double> p;
    std::string error;
    const nimbus_status_t s = emission_selection_.probabilities(p, error);
    if (s == NIMBUS_OK) emitters_.set_selection(p);
    if (s != NIMBUS_OK)
      log(NIMBUS_LOG_ERROR, "light sampler " + std::string(light_sampler()->desc->id) + ": " + error);
    return s;
  }

  // The photon and light paths' tracer for the scene as it is now.
  PhotonTracer tracer() const {
    sdk::TimedScene scene = timed_scene();
    scene.timed = merge_.clock.timed();  // a moving camera alone leaves photons untimed
    return PhotonTracer(host().get(), services(), light_selection(), emitters_, max_depth(), scene,
                        spectral());
  }

  nimbus_status_t photon_pass(uint32_t j, uint64_t paths, float filter_reach, PhotonPass::Result &result) {
    const nimbus_host_t *h = host().get();
    const uint32_t pass = uint32_t(split_.frame_number(j));  // keys its random numbers, as the radius
    if (progress_) progress_->report(h, 0, paths, "photons");
    PhotonTracer tracer = this->tracer();
    // Guided once some lookup has marked where the camera needs photons; a resumed render's rebuild finds
    // the frozen map its pass used in the saved state. A guided map's photons are not splatted.
    if (!rebuild_map_) pass_importance_ = guide_ ? importance_ : ImportanceMap(scene_center_, scene_radius_);
    const bool guided = guide_ && !pass_importance_.empty();
    lens_.bind(tracer, guided);
    if (guided) {
      if (nimbus_status_t s = pass_.run_guided(tracer, guide_, pass_importance_, tasks_, h, seed_, pass,
                                               paths, filter_reach, result);
          s != NIMBUS_OK) {
        log(NIMBUS_LOG_ERROR, "the photon guide failed; its photon pass could not be completed");
        return s;
      }
    } else if (nimbus_status_t s = pass_.run(tracer, tasks_, h, pass, paths, filter_reach, result);
               s != NIMBUS_OK) {
      return s;
    }
    if (progress_) progress_->report(h, paths, paths, "photons");
    // What camera passes read with this map (begin_iteration sets the radius, window and roulette).
    merge_.host = h, merge_.bsdf = services().bsdf, merge_.map = &pass_.map(), merge_.emitters = &emitters_;
    merge_.light_group = &light_groups(), merge_.ids = ids(), merge_.max_depth = max_depth();
    merge_.map_paths = result.paths, merge_.importance = &pass_importance_;
    merge_.importance_ratio = result.importance_ratio, merge_.path_use = &pass_.path_use();
    merge_.scene_radius = scene_radius_, merge_.density_weight = density_weights(emitters_);
    lens_.map_ready(guided, result.paths, merge_);
    photon_work_ = result.traced > 0 ? double(result.work) / double(result.traced) : 0.0;
    return NIMBUS_OK;
  }

  const nimbus_host_tasks_v1_t *tasks_ = nullptr;
  const nimbus_host_progress_v1_t *progress_ = nullptr;
  nimbus_element_t merge_element_ = NIMBUS_ELEMENT_INVALID, merge_id_ = NIMBUS_ELEMENT_INVALID;
  sdk::PerWorker<RadiusHistogram> lookup_radii_;  // radii of the lookups since the last photon pass
  sdk::PerWorker<uint64_t> region_pixels_;        // pixels rendered this iteration (per worker)
  sdk::PerWorker<CameraTally> tallies_;           // camera-path counts while a map is active
  sdk::PerWorker<ImportanceMarks> marks_;         // lookups that found light since the last iteration

  SolverOptions options_;  // the `caustics` switch and the measurement options
  PhotonBudget budget_{0};
  bool armed_ = false;     // enabled, and some light emits photons towards sharp geometry
  bool classify_ = false;  // camera passes without a map sort paths into the `caustics` element
  EmitterSet emitters_;
  float scene_radius_ = 1, theta_pix_ = 0;
  Vec3f scene_center_;
  uint32_t width_ = 0, height_ = 0;
  PhotonSchedule schedule_;
  sdk::TaskSplit split_;    // pass j is the frame's pass frame_number(j): docs/farm-rendering.md
  double photon_work_ = 0;  // work units per photon path of the last pass
  PhotonPass pass_;
  LensConnections lens_;      // splatted photons and light paths (lens_connections.hpp)
  uint64_t map_request_ = 0;  // photon paths asked of the current map's pass
  float map_reach_ = 0;       // and its occupancy filter's reach
  bool rebuild_map_ = false;  // resumed with a map active: trace it again before the next camera pass
  MergeContext merge_;        // what camera passes read while the map is active
  uint64_t seed_ = 0;
  GuideBinding guide_;                    // the bound guide's rev 2 table, if any
  ImportanceMap importance_;              // every successful lookup's mark so far (spec 6.3)
  ImportanceMap pass_importance_;         // the copy the current map's pass was guided by
  EmissionSelection emission_selection_;  // light selection for photon emission (spec 6.1)
  std::vector<uint64_t> pending_used_;    // a resumed map's lookup flags, until it is traced again
  bool map_active_ = false;
  UsefulPixels useful_;
  PixelRadius pixel_radius_;
  LookupRoulette roulette_;
  static constexpr uint32_t kStateVersion = 11;  // the format of save_state's bytes
  SolverStats stats_;
};

}  // namespace
}  // namespace nimbus::caustics

NIMBUS_PLUGIN_LIBRARY(nimbus::caustics::CausticsSolver)
