// The photon memory budget: a pass whose photons could need more memory than the budget traces fewer
// paths instead of failing for want of memory. Photons are counted at the per-path guard's worst case
// (photon_pass.cpp stops a task at kPhotonsPerPathCap photons per path), each costing its place in the
// task's chunk and its place in the map (with the map's index, measured on the last map), so the bound
// holds for any scene. The schedule then learns from the paths really traced.
#pragma once

#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <string>

#include "photon_map.hpp"
#include "photon_pass.hpp"

namespace nimbus::caustics {

class PhotonBudget {
 public:
  // megabytes: the budget in MiB; 0 picks a quarter of the machine's memory.
  explicit PhotonBudget(uint64_t megabytes) : bytes_(megabytes ? megabytes << 20 : quarter_of_memory()) {}

  uint64_t bytes() const { return bytes_; }

  // Paths a pass may trace: `paths` or fewer, so that the worst case fits. map_bytes_per_photon: of
  // the last map (0 before the first, then an estimate with the index is used).
  uint64_t paths_within(uint64_t paths, double map_bytes_per_photon) const {
    const double fit = double(bytes_) / worst_bytes(1, map_bytes_per_photon);
    return std::min<uint64_t>(paths, uint64_t(std::max(fit, 1.0)));
  }

  // The paths of a pass asked for `paths` after the map `last`; the first pass it cuts fills `warning`.
  uint64_t paths_for_pass(uint64_t paths, const PhotonKdTree &last, std::string &warning) {
    const double per_photon = last.size() ? double(last.bytes()) / double(last.size()) : 0;
    const uint64_t fit = paths_within(paths, per_photon);
    if (fit < paths && !warned_)
      warning = "a photon pass of " + std::to_string(paths) + " paths could need " +
                std::to_string(uint64_t(worst_bytes(paths, per_photon)) >> 20) +
                " MiB, over the photon memory budget of " + std::to_string(bytes_ >> 20) +
                " MiB: passes trace at most " + std::to_string(fit) + " paths";
    warned_ = warned_ || fit < paths;
    return fit;
  }

  // The worst-case bytes of a pass of `paths`: every path at the guard's cap, each photon in its chunk and
  // in the map (at least 1.5 photons' size with the index before the first map is measured), with its
  // splat in the chunk and in the pass.
  double worst_bytes(uint64_t paths, double map_bytes_per_photon) const {
    const double per_photon =
        std::max(map_bytes_per_photon, 1.5 * sizeof(Photon)) + sizeof(Photon) + 2.0 * sizeof(PhotonSplat);
    return double(paths) * double(kPhotonsPerPathCap) * per_photon;
  }

 private:
  static uint64_t quarter_of_memory() {
    const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
    return pages > 0 && page > 0 ? uint64_t(pages) * uint64_t(page) / 4 : uint64_t(1) << 30;
  }
  uint64_t bytes_;
  bool warned_ = false;  // a pass was cut (said once)
};

}  // namespace nimbus::caustics
