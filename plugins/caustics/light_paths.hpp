// The light-tracing technique (VCM's light-vertex connection to the camera): every camera pass that
// uses a photon map also traces light paths of its own, about one per pixel, from the finite lights by
// their power and the host's own emission (no projection map), through every vertex up to the maximum
// path length, and connects each rough vertex after the first bounce to the lens. It samples the
// indirect light of closed rooms under small lights (a floor lit by the walls) far better than path
// tracing does, and caustics seen after another diffuse bounce, which path tracing cannot sample under
// a delta light at all. Direct light (paths of two segments) stays path tracing's: NEE renders a small
// light's direct light nearly without noise, and the power heuristic, which weighs densities and not
// variances, would hand light tracing about half of it and add its Poisson noise.
//
// It joins the one power-heuristic combination of mis.hpp: the camera side carries its term R_lt from
// x_1 on (CameraMis::lt), with eta_lt = N_lt / C_1 as the splat technique's (mis.hpp, splat_eta), and
// evaluates its emission density lp_lt at every path end; the light side runs PhotonMis with lp_lt and
// the photon tracer's rules for where photons would have been stored, so the merges and splats it
// competes with are those the solver really has (rho = (lp_ph / lp_lt)^2 converts their densities).
// In a moving scene each light path has its own time, as a splatted photon does: no window of times,
// the merges' window share in their densities (merging.hpp, first_merge_densities). Off where a camera
// pass has no map, for dispersion, guided maps, pixel filters wider than a pixel and infinite lights,
// and where the render's own trial finds they do not pay (light_path_trial.hpp).
#pragma once

#include <nimbus/nimbus.hpp>

#include <cstdint>
#include <vector>

#include <nimbus/cpp/alias_table.hpp>
#include <nimbus/cpp/math.hpp>

#include "emitters.hpp"
#include "mis.hpp"

namespace nimbus::caustics {

struct MergeContext;
class PixelRadius;
class PhotonTracer;

// Budget work units (schedule.hpp) per ray of a light path: a ray's, kRayWork, and half again for what
// comes with it (a connection's BSDF evaluations and film writes, the camera side's extra MIS terms),
// so that the light-path trial compares the two arms' costs as the clock does (docs/performance.md §5).
inline constexpr uint64_t kLightPathRayWork = 3;

// Random-number stream of light path p of frame iteration i: derive(p, i, kStreamLightPath).
inline constexpr uint64_t kStreamLightPath = 0x6c7470617468;  // "ltpath"

// Which lights the light paths leave from, and lp_lt (mis.hpp notation) of a point and direction.
class LightPathEmission {
 public:
  // Finite lights by power; infinite lights emit no light paths (on open scenes light tracing loses).
  void build(const EmitterSet &emitters) {
    std::vector<double> w(emitters.size(), 0.0);
    for (size_t l = 0; l < w.size(); ++l)
      if (!emitters[l].infinite()) w[l] = double(emitters[l].power);
    table_ = AliasTable(w);
  }
  bool empty() const { return table_.empty(); }
  int64_t pick(float u, float *pmf) const { return table_.sample(u, pmf); }
  // lp_lt of light `l` emitting from z (normal n) along w: selection times the host's own densities
  // (the position's is 1 for delta positions, as in EmitterSet::lp). 0 for lights it never picks.
  float lp(const EmitterSet &emitters, uint32_t l, const Vec3f &z, const Vec3f &n, const Vec3f &w,
           float time = 0) const {
    const float sel = table_.pmf(l);
    if (!(sel > 0)) return 0;
    float pdf_pos = 1, pdf_dir = 0;
    emitters.own_pdfs(l, z, n, w, time, pdf_pos, pdf_dir);
    if (emitters[l].delta_position()) pdf_pos = 1;
    return sel * pdf_pos * pdf_dir;
  }

 private:
  AliasTable table_;
};

// log2 of rho = mis(lp_to / lp_from) (-inf when lp_to is 0): a photon stores it with lp_to = lp_lt and
// lp_from its own density, a light path with the two swapped.
inline float density_ratio_log2(float lp_to, float lp_from) {
  return lp_to > 0 && lp_from > 0 ? float(2 * std::log2(double(lp_to) / double(lp_from)))
                                  : -std::numeric_limits<float>::infinity();
}

// Weight of connecting a light path's vertex x_1 to the lens (the light-tracing technique).
//   log2_A, log2_B, b_valid: its PhotonMis state at x_1 (run with lp_lt)
//   v1:        the photon tracer would have stored a photon at x_1 that the camera's lookup finds
//   w_cam_fwd: omega^C_1 of the light path's incoming direction, given the camera's
//   eta, neff, neff_b: the merge at x_1's densities (merge_densities), eta_splat: mis(splat_eta) while
//              photons are splatted and v1 (else 0)
//   rho:       mis(lp_ph / lp_lt), the merges' and splats' density against this path's
//   eta_lt:    mis(splat_eta(N_lt, C_1))
inline float lt_weight(float log2_A, float log2_B, bool b_valid, bool v1, float w_cam_fwd, Mis eta, Mis neff,
                       Mis neff_b, Mis eta_splat, Mis rho, Mis eta_lt, bool &clamped) {
  if (!(eta_lt > 0)) return 0.0f;
  const Mis w2 = mis(Mis(w_cam_fwd));
  Mis others = w2 * std::exp2(Mis(log2_A));
  if (rho > 0) {
    Mis merges = v1 ? eta + eta_splat : 0.0;
    if (b_valid && neff > 0) merges += w2 * std::exp2(Mis(log2_B)) * neff_b * eta / neff;
    others += rho * merges;
  }
  others /= eta_lt;
  if (!(others <= std::numeric_limits<Mis>::max())) clamped = true;
  return mis_weight(others);
}

// What a light path's vertex is to the other techniques.
struct LightVertexClass {
  uint32_t light = 0, depth = 0;  // its light; segments from the light (it completes depth + 1)
  bool stored = false;            // the photon tracer would have stored a photon here
  Mis rho = 0;                    // mis(lp_ph / lp_lt) of the path's emission
  float time = 0, time_u = 0;     // the path's scene time and its share of the exposure (0: static)
};

// Light (luminance) a connection added to pixel `pixel` (light_path_trial.hpp).
struct PixelLight {
  uint32_t pixel;
  float light;
};

// What one camera pass's light paths read (fixed during the pass).
struct LightTracing {
  const nimbus_host_film_v1_t *film = nullptr;
  const nimbus_ext_lightmix_v1_t *lightmix = nullptr;  // null unless LightMix is active
  const MergeContext *merge = nullptr;                 // its lt_paths is N_lt
  const PixelRadius *pixel_radius = nullptr;
  uint32_t width = 0, height = 0;
  uint64_t iteration = 0;     // the frame iteration: keys the paths' random numbers
  bool record_light = false;  // record each connection's light per pixel (LightTally::light)
};

// What one worker's light paths counted.
struct LightTally {
  uint64_t work = 0;              // budget work units (schedule.hpp)
  uint64_t splats = 0;            // connections that reached the film
  uint64_t clamped = 0;           // weights whose competitors overflowed
  std::vector<PixelLight> light;  // with LightTracing::record_light: each connection's, in path order
};

// [main-thread] Traces the camera pass's in.merge->lt_paths light paths with `tracer` (in parallel) and
// adds their counts (and recorded light, in path order) to `tally`. Deterministic: the film sums splats
// per pixel in a fixed order.
nimbus_status_t trace_light_paths(const PhotonTracer &tracer, const nimbus_host_tasks_v1_t *tasks,
                                  const nimbus_host_t *h, const LightTracing &in, LightTally &tally);

}  // namespace nimbus::caustics
