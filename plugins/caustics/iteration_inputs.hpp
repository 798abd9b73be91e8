// What one camera iteration tells the photon schedule's efficiency model and the lookup roulette
// (solver spec 5): the variances of its window and the work per path of each side.
#pragma once

#include <algorithm>
#include <cstdint>

#include "lookup_roulette.hpp"
#include "merging.hpp"
#include "schedule.hpp"
#include "useful_pixels.hpp"

namespace nimbus::caustics {

struct IterationInputs {
  RouletteSample roulette;
  EfficiencySample efficiency;
  // Work per camera path of the whole iteration: paths, lookups, light paths, the map's photon paths.
  double work() const {
    double w = roulette.other_work;
    for (double l : roulette.lookup_work) w += l;
    return w;
  }
};

// sum: the camera paths' tally; camera_extra: other camera-pass work (light paths); pixels: camera
// paths; rho: the map's photon paths per camera path; photon_work: work per photon path of its pass.
inline IterationInputs iteration_inputs(const UsefulPixels::Summary &summary, const CameraTally &sum,
                                        uint64_t camera_extra, uint64_t pixels, double rho,
                                        double photon_work) {
  const double n_cam = double(std::max<uint64_t>(1, pixels));
  const double camera_work = double(sum.work + camera_extra) / n_cam;
  uint64_t lookup_work = 0;
  for (uint64_t w : sum.lookup_work) lookup_work += w;
  IterationInputs in;
  in.roulette = {
      summary.v_camera + summary.v_merge, summary.second_moment, camera_work + rho * photon_work, {}};
  for (uint32_t c = 0; c < kLookupClasses; ++c)
    in.roulette.lookup_work[c] = double(sum.lookup_work[c]) / n_cam;
  const double per_photon_path = photon_work + (rho > 0 ? double(lookup_work) / (rho * n_cam) : 0.0);
  in.efficiency = {summary.v_merge, summary.v_camera, rho, camera_work, per_photon_path};
  return in;
}

}  // namespace nimbus::caustics
