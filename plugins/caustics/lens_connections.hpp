// The techniques that connect light-side vertices to the lens: stored photons (the splat technique,
// photon_splats.hpp) and the vertices of light paths of their own (the light-tracing technique,
// light_paths.hpp). Whether a render and each map can use them (and whether light paths pay:
// light_path_trial.hpp), what they tell the photon tracer and the camera side (MergeContext), and their
// work in every camera pass that uses a map.
#pragma once

#include <nimbus/nimbus.hpp>

#include <algorithm>

#include "light_path_trial.hpp"
#include "light_paths.hpp"
#include "merging.hpp"
#include "photon_splats.hpp"
#include "photon_tracer.hpp"
#include "solver_stats.hpp"

namespace nimbus::caustics {

class LensConnections {
 public:
  // [main-thread, prepare] Splatted photons are light of the `caustics` element (diverted) too, and
  // light paths of the lighting elements.
  static void register_elements(const nimbus_host_film_v1_t *film, const nimbus_host_t *h,
                                const char *diverted) {
    for (const char *el : {diverted, "direct", "indirect"})
      film->register_element(h, el, 3, NIMBUS_ELEMENT_SPLAT);
  }

  // [main-thread] A new render. splats: photons can be splatted (splats_possible, lookups that match
  // photon times); light paths need the same. axis, theta_pix: the view axis and a pixel's angular width
  // (camera_density).
  void begin_render(const EmitterSet &emitters, bool splats, const Vec3f &axis, float theta_pix,
                    uint64_t pixels, MergeContext &merge) {
    splat_camera_ = {splats, axis, theta_pix};
    emission_.build(emitters);
    light_paths_ = splats && !emission_.empty();
    map_light_paths_ = false;
    paths_ = std::max<uint64_t>(1, pixels), work_ = 0;
    trial_.reset(pixels, light_paths_), measuring_ = false;
    merge.view_axis = axis, merge.theta_pix = theta_pix;
    merge.lt_emission = &emission_, merge.lt_paths = 0, merge.splat_paths = 0;
  }

  // [main-thread] A photon pass: its tracer splats photons and rates them against light paths unless
  // the map is guided (its photons weigh merges by importance, which neither technique follows).
  void bind(PhotonTracer &tracer, bool guided) {
    tracer.connect_to(guided ? SplatCamera{} : splat_camera_);
    map_light_paths_ = light_paths_ && !guided;
    tracer.light_paths_from(map_light_paths_ ? &emission_ : nullptr);
  }
  // [main-thread] The map of that pass, of N_u uniform photon paths, is ready.
  void map_ready(bool guided, uint64_t photon_paths, MergeContext &merge) const {
    merge.splat_paths = splat_camera_.enabled && !guided ? double(photon_paths) : 0.0;
  }

  // [main-thread] The camera pass of frame iteration `iteration`: with a map active, its photons'
  // splats, then its light paths (about one per camera path of the last iteration) when the trial
  // (light_path_trial.hpp) has them in this pass.
  nimbus_status_t camera_pass(bool map_active, SplatInputs splats, const PhotonTracer &tracer,
                              uint64_t iteration, MergeContext &merge, SolverStats &stats) {
    merge.lt_paths = map_active && map_light_paths_ && trial_.light_paths() ? double(paths_) : 0.0;
    measuring_ = merge.lt_paths > 0 && trial_.measuring();
    splats.trial = measuring_ ? &trial_ : nullptr;
    if (map_active && merge.splat_paths > 0)
      if (nimbus_status_t s = splat_photons(splats, stats.mis_clamped); s != NIMBUS_OK) return s;
    if (!(merge.lt_paths > 0)) return NIMBUS_OK;
    LightTally t;
    const LightTracing in{splats.film,  splats.lightmix, &merge,    splats.pixel_radius,
                          splats.width, splats.height,   iteration, measuring_};
    const nimbus_status_t s = trace_light_paths(tracer, splats.tasks, splats.host, in, t);
    stats.light_paths += paths_, stats.light_splats += t.splats, stats.mis_clamped += t.clamped;
    for (const PixelLight &l : t.light) trial_.add_splat(l.pixel, l.light, 0.0f);
    work_ += t.work;
    return s;
  }
  // [render-thread] Pixel i's camera sample in the current pass.
  void add_sample(size_t i, const CausticsRecord &rec) {
    if (measuring_) trial_.add_sample(i, luminance(rec.beauty), luminance(rec.without_light_paths));
  }
  // [main-thread] The current pass ended with `work` work units per camera path, all included.
  void pass_done(double work) {
    if (measuring_) trial_.pass_done(work, pass_work_);
  }
  LightPathTrial &trial() { return trial_; }
  // [main-thread] The trial's outcome as render statistics.
  void report(const nimbus_host_progress_v1_t *progress, const nimbus_host_t *h) const {
    const LightPathTrial::Decision &d = trial_.decision();
    progress->stat_add(h, "caustics_light_paths_kept", trial_.state() == LightPathTrial::State::On ? 1 : 0);
    progress->stat_add(h, "caustics_light_path_trial_variance_without", d.v_off);
    progress->stat_add(h, "caustics_light_path_trial_variance_with", d.v_on);
    progress->stat_add(h, "caustics_light_path_trial_work_without", d.c_off);
    progress->stat_add(h, "caustics_light_path_trial_work_with", d.c_on);
  }

  // [main-thread] An iteration ended with `pixels` camera paths: the light paths' work since the last
  // call (camera-pass work in the budget's model), and their count for the next passes.
  uint64_t iteration_done(uint64_t pixels) {
    paths_ = std::max<uint64_t>(1, pixels);
    pass_work_ = double(work_) / double(paths_);
    return std::exchange(work_, 0);
  }

 private:
  SplatCamera splat_camera_;      // how photon passes connect photons to the lens
  LightPathEmission emission_;    // the light paths' lights
  bool light_paths_ = false;      // the render can trace light paths
  bool map_light_paths_ = false;  // and the current map's camera passes do
  uint64_t paths_ = 0;            // light paths per camera pass
  uint64_t work_ = 0;             // their budget work units since the last iteration_done
  LightPathTrial trial_;          // whether they pay
  bool measuring_ = false;        // the current pass traces light paths for the trial
  double pass_work_ = 0;          // their work per camera path in the last pass
};

}  // namespace nimbus::caustics
