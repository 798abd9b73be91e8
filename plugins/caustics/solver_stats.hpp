// The caustics solver's render statistics: counted over the render (and kept in its checkpoints), then
// reported once through the host's progress service as "caustics_*" entries of the output's metadata.
#pragma once

#include <nimbus/nimbus.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <nimbus/cpp/math.hpp>

namespace nimbus::caustics {

struct SolverStats {
  uint64_t photon_paths = 0, photons = 0, photon_bytes = 0, passes = 0, map_iterations = 0;
  uint64_t mis_clamped = 0;
  uint64_t first_lookups = 0, shrunk_lookups = 0;  // first lookups, and those with a per-pixel radius
  uint64_t guided_passes = 0, proposals = 0, accepted = 0;
  uint64_t used_paths = 0;  // photon paths of finished maps that some lookup used
  uint64_t splats = 0;      // stored photons the lens sees (photon_splats.hpp), over the passes
  uint64_t light_paths = 0, light_splats = 0;  // the light-tracing technique's (light_paths.hpp)
  double photon_seconds = 0;                   // photon tracing and kd-tree builds
  // The flux each pass's stored photons carry (the luminance of their powers over the pass's uniform path
  // count, as lookups normalise them): its sum and sum of squares over the passes. Every pass estimates
  // the same flux independently, so their spread gives its standard error (energy tests, spec 10 v).
  double flux_sum = 0, flux_sq = 0;

  // What the rest of the solver knows at the end: the budget's photon ratio, the lookup roulette's
  // probabilities, the importance map's size, and a photon's size in bytes.
  struct Final {
    double photon_ratio = 0, lookup_first = 1, lookup_later = 1, importance_cells = 0, photon_size = 0;
    double emission_slots = 0;  // projection-map components with a learnt emission density
  };

  // [main-thread] A photon pass (photon_pass.hpp's Result), its map (photons, bytes), its seconds.
  template <class PassResult, class Map>
  void pass_done(const PassResult &r, const Map &map, double seconds) {
    photon_paths += r.traced, proposals += r.proposals, accepted += r.accepted;
    guided_passes += r.importance_ratio > 0 ? 1 : 0;
    photons += map.size(), photon_bytes += map.bytes(), photon_seconds += seconds;
    double flux = 0;
    for (size_t i = 0; i < map.size(); ++i) flux += luminance(Vec3f::load(map.data()[i].power));
    flux = r.paths > 0 ? flux / double(r.paths) : 0.0;
    flux_sum += flux, flux_sq += flux * flux;
    ++passes;
  }

  // [main-thread] One worker's camera-path counts (merging.hpp's CameraTally) of an iteration.
  template <class Tally>
  void camera_done(const Tally &t) {
    mis_clamped += t.mis_clamped, first_lookups += t.first_lookups, shrunk_lookups += t.shrunk_lookups;
  }

  // [main-thread]
  void report(const nimbus_host_progress_v1_t *progress, const nimbus_host_t *h, const Final &f) const {
    const auto ratio = [](uint64_t a, uint64_t b) { return b > 0 ? double(a) / double(b) : 0.0; };
    progress->stat_add(h, "caustics_photon_paths", double(photon_paths));
    progress->stat_add(h, "caustics_photons", double(photons));
    progress->stat_add(h, "caustics_photon_passes", double(passes));
    progress->stat_add(h, "caustics_map_iterations", double(map_iterations));
    progress->stat_add(h, "caustics_photon_seconds", photon_seconds);
    progress->stat_add(h, "caustics_splats", double(splats));
    progress->stat_add(h, "caustics_light_paths", double(light_paths));
    progress->stat_add(h, "caustics_light_splats", double(light_splats));
    // The flux of a pass's stored photons: the mean over the passes and its standard error.
    const double mean_flux = passes > 0 ? flux_sum / double(passes) : 0.0;
    const double flux_var =
        passes > 1 ? std::max(0.0, flux_sq / double(passes) - mean_flux * mean_flux) : 0.0;
    progress->stat_add(h, "caustics_photon_flux", mean_flux);
    progress->stat_add(h, "caustics_photon_flux_se",
                       passes > 1 ? std::sqrt(flux_var / double(passes - 1)) : 0.0);
    // Camera paths whose MIS weights met an overflow (mis.hpp): 0 in any sane scene.
    progress->stat_add(h, "caustics_mis_clamped", double(mis_clamped));
    progress->stat_add(h, "caustics_photon_ratio", f.photon_ratio);
    // Photon guiding (spec 6.3): passes whose paths a guide chose, its proposals' acceptance and the
    // importance map's marked cells.
    progress->stat_add(h, "caustics_guided_passes", double(guided_passes));
    progress->stat_add(h, "caustics_guide_acceptance", ratio(accepted, proposals));
    progress->stat_add(h, "caustics_importance_cells", f.importance_cells);
    progress->stat_add(h, "caustics_emission_map_slots", f.emission_slots);
    // Share of the traced photon paths (of finished maps) whose photons some lookup used.
    progress->stat_add(h, "caustics_used_path_fraction", ratio(used_paths, photon_paths));
    // The lookup roulette's final probabilities (lookup_roulette.hpp).
    progress->stat_add(h, "caustics_lookup_probability_first", f.lookup_first);
    progress->stat_add(h, "caustics_lookup_probability_later", f.lookup_later);
    // Share of first lookups whose pixel's photon density shrank the radius (pixel_radius.hpp).
    progress->stat_add(h, "caustics_pixel_radius_shrunk", ratio(shrunk_lookups, first_lookups));
    progress->stat_add(h, "caustics_bytes_per_photon",
                       photons > 0 ? double(photon_bytes) / double(photons) : f.photon_size);
  }
};

}  // namespace nimbus::caustics
