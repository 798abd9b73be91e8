// One photon pass (solver spec section 5): photon paths traced as host tasks into per-task chunks,
// concatenated in task order (photon indices never depend on threads), and the photon map rebuilt. The
// buffers keep their memory from pass to pass, so a pass does not pay first-touch page faults on freshly
// allocated pages.
#pragma once

#include <nimbus/nimbus.hpp>

#include <vector>

#include <nimbus/cpp/rng.hpp>

#include "emitters.hpp"
#include "occupancy_filter.hpp"
#include "photon_map.hpp"
#include "photon_tracer.hpp"

namespace nimbus::caustics {

// The i-th path a task of pass `pass` traces in its run [b, e): the run rotated by an offset hashed from
// the pass and the run, so that a task cut short by its memory guard leaves out different paths (and
// emission strata) in every pass.
inline uint64_t task_path(uint32_t pass, uint64_t b, uint64_t e, uint64_t i) {
  const uint64_t n = e - b;
  return b + (i + hash_keys({pass, b}) % n) % n;
}

class PhotonPass {
 public:
  struct Result {
    uint64_t paths = 0;  // photon paths completed (N_eff of the new map)
    uint64_t work = 0;   // budget work units (schedule.hpp)
  };

  // [main-thread] Traces `paths` photon paths of pass `pass` (1-based) and rebuilds the map, with an
  // occupancy filter of reach `filter_reach` (0: none). The same arguments give the same map.
  nimbus_status_t run(const PhotonTracer &tracer, const nimbus_host_tasks_v1_t *tasks, const nimbus_host_t *h,
                      uint32_t pass, uint64_t paths, float filter_reach, Result &result);

  // [main-thread] The occupancy filter's reach for the next map: the radius 95 % of the lookups since the
  // last pass stayed within (radii only shrink from pass to pass), so nearly every lookup can ask the
  // filter first. Empties the histograms.
  static float filter_reach(sdk::PerWorker<RadiusHistogram> &lookup_radii);

  const PhotonKdTree &map() const { return map_; }
  // [main-thread] Frees the map and the buffers (end of a render).
  void release();

 private:
  std::vector<PhotonChunk> chunks_;  // one buffer per task
  std::vector<Photon> photons_;      // the tasks' photons in task order
  PhotonKdTree map_;
};

}  // namespace nimbus::caustics
