// The techniques that connect light-side vertices to the lens: stored photons (the splat technique,
// photon_splats.hpp) and the vertices of light paths of their own (the light-tracing technique,
// light_paths.hpp). Whether a render and each map can use them, what they tell the photon tracer and
// the camera side (MergeContext), and their work in every camera pass that uses a map.
#pragma once

#include <nimbus/nimbus.hpp>

#include <algorithm>

#include "light_paths.hpp"
#include "merging.hpp"
#include "photon_splats.hpp"
#include "photon_tracer.hpp"
#include "solver_stats.hpp"

namespace nimbus::caustics {

class LensConnections {
 public:
  // [main-thread] A new render. splats: photons can be splatted (splats_possible, lookups that match
  // photon times); timed: photons carry scene times (no light paths then: their weights would need the
  // merges' time windows). axis, theta_pix: the view axis and a pixel's angular width (camera_density).
  void begin_render(const EmitterSet &emitters, bool splats, bool timed, const Vec3f &axis, float theta_pix,
                    uint64_t pixels, MergeContext &merge) {
    splat_camera_ = {splats, axis, theta_pix};
    emission_.build(emitters);
    light_paths_ = splats && !timed && !emission_.empty();
    map_light_paths_ = false;
    paths_ = std::max<uint64_t>(1, pixels), work_ = 0;
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
  // splats, then its light paths (about one per camera path of the last iteration).
  nimbus_status_t camera_pass(bool map_active, const SplatInputs &splats, const PhotonTracer &tracer,
                              uint64_t iteration, MergeContext &merge, SolverStats &stats) {
    merge.lt_paths = map_active && map_light_paths_ ? double(paths_) : 0.0;
    if (map_active && merge.splat_paths > 0)
      if (nimbus_status_t s = splat_photons(splats, stats.mis_clamped); s != NIMBUS_OK) return s;
    if (!(merge.lt_paths > 0)) return NIMBUS_OK;
    LightTally t;
    const LightTracing in{splats.film,  splats.lightmix, &merge,   splats.pixel_radius,
                          splats.width, splats.height,   iteration};
    const nimbus_status_t s = trace_light_paths(tracer, splats.tasks, splats.host, in, t);
    stats.light_paths += paths_, stats.light_splats += t.splats, stats.mis_clamped += t.clamped;
    work_ += t.work;
    return s;
  }

  // [main-thread] An iteration ended with `pixels` camera paths: the light paths' work since the last
  // call (camera-pass work in the budget's model), and their count for the next passes.
  uint64_t iteration_done(uint64_t pixels) {
    paths_ = std::max<uint64_t>(1, pixels);
    return std::exchange(work_, 0);
  }

 private:
  SplatCamera splat_camera_;      // how photon passes connect photons to the lens
  LightPathEmission emission_;    // the light paths' lights
  bool light_paths_ = false;      // the render can trace light paths
  bool map_light_paths_ = false;  // and the current map's camera passes do
  uint64_t paths_ = 0;            // light paths per camera pass
  uint64_t work_ = 0;             // their budget work units since the last iteration_done
};

}  // namespace nimbus::caustics
