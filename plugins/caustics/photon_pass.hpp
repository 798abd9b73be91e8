// One photon pass (solver spec section 5): photon paths traced as host tasks into per-task chunks,
// concatenated in task order (photon indices never depend on threads), and the photon map rebuilt. The
// buffers keep their memory from pass to pass, so a pass does not pay first-touch page faults on freshly
// allocated pages.
#pragma once

#include <nimbus/nimbus.hpp>

#include <span>
#include <vector>

#include <nimbus/cpp/rng.hpp>

#include "emitters.hpp"
#include "importance_map.hpp"
#include "occupancy_filter.hpp"
#include "path_use.hpp"
#include "photon_map.hpp"
#include "photon_tracer.hpp"

namespace nimbus::caustics {

// A task stops tracing when its buffer holds this many photons per path (a memory guard far above what
// caustic scenes store). A task that stops early leaves part of its run of emission strata
// (emission_strata.hpp) unsampled; task_path() starts each pass's run at another place, so the paths
// left out differ from pass to pass and the map normalised by the completed paths has no fixed hole.
constexpr uint64_t kPhotonsPerPathCap = 4;

// Chains per guided photon pass: fixed, so that the photons do not depend on the thread count.
inline constexpr uint32_t kGuideChains = 256;

// A guide bound to the render that serves "nimbus.iface.guiding" rev 2 (host-owned).
struct GuideBinding {
  const nimbus_plugin_t *plugin = nullptr;
  const nimbus_guiding_v2_t *iface = nullptr;
  explicit operator bool() const { return plugin && iface; }
  // The binding of `guide` (borrowed for the render; null: none), or none when it lacks rev 2.
  static GuideBinding of(const nimbus_plugin_t *guide) {
    const auto *t =
        guide ? static_cast<const nimbus_guiding_v2_t *>(guide->get_interface(guide, NIMBUS_IFACE_GUIDING, 2))
              : nullptr;
    return t && t->struct_size >= sizeof(nimbus_guiding_v2_t) ? GuideBinding{guide, t} : GuideBinding{};
  }
};

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
    uint64_t paths = 0;   // N_u: uniform photon paths completed (the map's photon count per unit density)
    uint64_t traced = 0;  // photon paths traced, guided proposals included (the budget's count)
    uint64_t work = 0;    // budget work units (schedule.hpp)
    // Guided passes (spec 6.3): c = N_m / (N_u b^), so the effective photon count at x is
    // N_u (1 + c I(x)); 0 without guiding. Chain proposals and those that became a chain state.
    double importance_ratio = 0;
    uint64_t proposals = 0, accepted = 0;
    bool guided = false;  // the paths came from the guide's Markov chains (not independent)
  };

  // [main-thread] Traces `paths` photon paths of pass `pass` (1-based) and rebuilds the map, with an
  // occupancy filter of reach `filter_reach` (0: none). The same arguments give the same map.
  nimbus_status_t run(const PhotonTracer &tracer, const nimbus_host_tasks_v1_t *tasks, const nimbus_host_t *h,
                      uint32_t pass, uint64_t paths, float filter_reach, Result &result);

  // [main-thread] The same, with the paths chosen by `guide`'s chains on the target of `importance` (a
  // frozen copy that camera passes read with this map): the photons get the mixture weights of spec 6.3
  // and their B its effective counts. seed: the render's. Fails with the guide's status if a chain fails.
  nimbus_status_t run_guided(const PhotonTracer &tracer, const GuideBinding &guide,
                             const ImportanceMap &importance, const nimbus_host_tasks_v1_t *tasks,
                             const nimbus_host_t *h, uint64_t seed, uint32_t pass, uint64_t paths,
                             float filter_reach, Result &result);

  // [main-thread] The occupancy filter's reach for the next map: the radius 95 % of the lookups since the
  // last pass stayed within (radii only shrink from pass to pass), so nearly every lookup can ask the
  // filter first. Empties the histograms.
  static float filter_reach(sdk::PerWorker<RadiusHistogram> &lookup_radii);

  const PhotonKdTree &map() const { return map_; }
  // The map's photons in pass order, and their connections to the lens (photon_splats.hpp).
  std::span<const Photon> photons() const { return photons_; }
  std::span<const PhotonSplat> splats() const { return splats_; }
  // The map's paths: their lights, and which of them camera lookups used.
  PathUse &path_use() { return use_; }
  const PathUse &path_use() const { return use_; }
  // [main-thread] Frees the map and the buffers (end of a render).
  void release();

 private:
  // The chunks' photons in chunk order, then the map (with the photons' times and wavelengths when
  // `tracer`'s photons carry them).
  void assemble(const sdk::ParallelFor &parallel, float filter_reach, const PhotonTracer &tracer);

  std::vector<PhotonChunk> chunks_;  // one buffer per task
  std::vector<Photon> photons_;      // the tasks' photons in task order
  std::vector<PhotonSplat> splats_;  // their splats, in the same order
  PhotonKdTree map_;
  PathUse use_;
};

}  // namespace nimbus::caustics
