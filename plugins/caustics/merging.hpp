// The camera side of photon merging (solver spec sections 3.3-3.5): the path extension of the camera-path
// layer that a camera pass uses while a photon map is active. The same path (same random numbers) as
// nimbus.pt also carries the MIS state, looks photons up at its rough vertices and weights BSDF hits and
// next-event estimation against merging (mis.hpp), so the techniques form one power-heuristic combination.
#pragma once

#include <nimbus/nimbus.hpp>

#include <array>
#include <vector>

#include <nimbus/cpp/camera_path.hpp>

#include "caustics_record.hpp"
#include "emitters.hpp"
#include "importance_map.hpp"
#include "light_paths.hpp"
#include "lookup_roulette.hpp"
#include "mis.hpp"
#include "occupancy_filter.hpp"
#include "path_use.hpp"
#include "photon_map.hpp"
#include "photon_windows.hpp"
#include "pixel_radius.hpp"
#include "schedule.hpp"
#include "sharpness.hpp"

namespace nimbus::caustics {

// What merging reads during a camera pass: fixed from begin_iteration to end_iteration.
struct MergeContext {
  const nimbus_host_t *host = nullptr;
  const nimbus_host_bsdf_v1_t *bsdf = nullptr;
  const PhotonKdTree *map = nullptr;
  const EmitterSet *emitters = nullptr;
  const std::vector<uint32_t> *light_group = nullptr;  // LightMix group of each light
  ElementIds ids;
  uint32_t max_depth = 0;
  uint64_t map_paths = 0;  // N_u: uniform photon paths behind the map
  // Photon guiding (spec 6.3): the effective photon count at x is N_u (1 + importance_ratio I(x)), I from
  // the importance map the map's pass used (null, and ratio 0, without guiding).
  const ImportanceMap *importance = nullptr;
  double importance_ratio = 0;
  PathUse *path_use = nullptr;        // the map's paths: lookups flag those whose photons contributed
  std::vector<float> density_weight;  // per light, what its photons count in a pixel's density (below)
  float radius_per_length = 0;        // merge radius per unit path length at the map's pass
  PhotonClock clock;                  // photon times (spec 7.1): untimed unless geometry or lights move
  float time_half_width = 0;          // h of the map's pass
  // Dispersion (spec 7.2): the host's spectral service when the scene disperses light (else null), and
  // the half width (nm) of the wavelength window of the map's pass.
  const nimbus_host_spectral_v1_t *spectral = nullptr;
  float lambda_half_width = 0;
  float scene_radius = 1;
  // The splat technique (photon_splats.hpp): N_u while the map's photons are splatted (0: no splats),
  // and the view axis and pixel width its camera density reads (mis.hpp, camera_density).
  double splat_paths = 0;
  Vec3f view_axis{0, 0, 1};
  float theta_pix = 0;
  // The light-tracing technique (light_paths.hpp): N_lt, its light paths per camera pass (0: off), and
  // their emission.
  double lt_paths = 0;
  const LightPathEmission *lt_emission = nullptr;
  // Lookup probability per class of rough vertex (lookup_roulette.hpp), set before each camera pass.
  std::array<float, kLookupClasses> lookup_probability{1.0f, 1.0f};
  // The merge technique's factor on the photon density in MIS at the lookup vertex with `rough_count`
  // rough vertices up to it: its class's lookup probability times lookup_rank_factor.
  Mis lookup_mis_density(uint32_t rough_count) const {
    return Mis(lookup_probability[lookup_class(rough_count)]) * lookup_rank_factor(rough_count);
  }
};

// The merge technique's densities in MIS at the lookup vertex with `rough_count` rough vertices up to it,
// radius r, effective photon count neff (times the time window's share rho): eta = mis(pi r^2 neff q),
// neff = mis(neff q), and neff_b, the count at the photon's rough vertices (B) as seen from the next rough
// vertex (B carries each further one's rank factor). merge_photons and the splats' weights share it.
struct MergeDensities {
  Mis eta, neff, neff_b;
};
inline MergeDensities merge_densities(const MergeContext &mc, float r, float neff, uint32_t rough_count,
                                      float rho) {
  const Mis q_mis = mc.lookup_mis_density(rough_count), r2 = Mis(r) * r;
  return {mis(kPi * r2 * Mis(neff) * q_mis), mis(Mis(neff) * q_mis),
          mis(Mis(mc.map_paths) * mc.lookup_mis_density(rough_count + 1) * rho)};
}

// The densities of the first lookup of a camera path through `pixel` whose first vertex lies at
// distance `length` (the pixel's radius, the first lookup's probability, the time window around time_u):
// what a connection of x_1 to the lens competes with (the splat and light-tracing techniques).
inline MergeDensities first_merge_densities(const MergeContext &mc, const PixelRadius &pixel_radius,
                                            size_t pixel, float length, float time_u) {
  const TimeWindow window = mc.clock.window(time_u, mc.time_half_width);
  const float neff = float(mc.map_paths) * window.rho;
  const float r =
      pixel_radius.radius(pixel, merge_radius(mc.radius_per_length, length, mc.scene_radius), neff);
  return merge_densities(mc, r, neff, 1, window.rho);
}

// The most a photon of a rarely chosen light counts in a pixel's photon density.
inline constexpr float kMaxDensityWeight = 8;

// Per light, what one of its photons counts in a pixel's photon density (pixel_radius.hpp): the most
// likely light's selection probability over its own (at most kMaxDensityWeight). The density is then
// that of the light's own photon paths as if it had the most likely light's share: a focus shrinks the
// kernel alike whichever light forms it, so two mirror-symmetric LightMix groups with unequal photon
// shares keep mirror-symmetric radii (and layers).
inline std::vector<float> density_weights(const EmitterSet &emitters) {
  std::vector<float> w(emitters.size(), 0.0f);
  float most = 0;
  for (size_t l = 0; l < w.size(); ++l) most = std::max(most, emitters.selection_pmf(uint32_t(l)));
  for (size_t l = 0; l < w.size(); ++l) {
    const float pmf = emitters.selection_pmf(uint32_t(l));
    w[l] = pmf > 0 ? std::min(kMaxDensityWeight, most / pmf) : 0.0f;
  }
  return w;
}

// What one lookup did: for the budget's work count, kd-tree leaves scanned and photons evaluated; for
// the lookup roulette, the luminance of the light it added; for the pixel's density, the photons it
// evaluated, each counted by its light's density weight.
struct LookupCost {
  uint32_t leaves = 0, evaluated = 0;
  float light = 0;
  float density_count = 0;
  uint64_t work() const { return kLeafWork * leaves + kPhotonWork * evaluated; }
};

// Photon lookup at the lookup vertex x_s (spec 3.4): Epanechnikov kernel of radius r, MIS-weighted merges.
// rough_count: the rough vertices up to x_s; its class's lookup probability q the merges count 1/q times,
// and MergeContext::lookup_mis_density scales the merge technique's density in the weights. neff: the
// effective photon count at x_s, times the window's share rho of photon times. window: the photon times the
// lookup accepts (photon_windows.hpp). lambda: the camera path's wavelength (0 while it carries RGB).
// eta_splat: mis(splat_eta) at x_1 while photons are splatted, else 0.
LookupCost merge_photons(const MergeContext &mc, const nimbus_interaction_t &ix, const Vec3f &wo,
                         const Rgb &beta, const CameraMis &mis_state, float r, uint32_t s,
                         uint32_t rough_count, float neff, const TimeWindow &window, float lambda,
                         Mis eta_splat, CausticsRecord &rec);

// The effective photon count at x (spec 6.3): N_u, raised where the guide's chains aimed.
inline float effective_photons(const MergeContext &mc, const Vec3f &x) {
  const double n = double(mc.map_paths);
  if (!(mc.importance_ratio > 0) || !mc.importance) return float(n);
  return float(n * (1.0 + mc.importance_ratio * double(mc.importance->at(x))));
}

// lp (mis.hpp) of the light a camera path hit, and of the one its NEE sampled: the photon density of
// the path's last segment, 0 where no photon is emitted that way (then no merge technique exists).
inline float hit_lp(const EmitterSet &emitters, const sdk::LightHit &h) {
  return emitters.lp(h.light, h.p, h.n, h.wo, Vec3f::load(h.prev->p), h.time);
}
inline float nee_lp(const EmitterSet &emitters, const sdk::LightSample &s) {
  return emitters.lp(s.light, Vec3f::load(s.ls->p), Vec3f::load(s.ls->n), -s.wi, Vec3f::load(s.ix->p),
                     s.time);
}

// What one worker's camera paths counted while a map was active.
struct CameraTally {
  uint64_t work = 0;                                      // budget work units (schedule.hpp) of the paths
  std::array<uint64_t, kLookupClasses> lookup_work = {};  // and of their lookups (LookupCost), per class
  uint64_t mis_clamped = 0;                               // paths whose MIS weights met an overflow
  uint64_t first_lookups = 0, shrunk_lookups = 0;  // first lookups, and those below the schedule radius
};

// One iteration's camera work, summed over the workers' tallies (which restart empty); `each` sees every
// tally first (the render statistics).
template <class Tallies, class Each>
CameraTally sum_tallies(Tallies &tallies, Each &&each) {
  CameraTally sum;
  for (CameraTally &t : tallies) {
    each(t);
    sum.work += t.work;
    for (uint32_t c = 0; c < kLookupClasses; ++c) sum.lookup_work[c] += t.lookup_work[c];
    t = {};
  }
  return sum;
}

class MergingPath {
 public:
  static constexpr bool kReversePdfs = true;

  // tally: this worker's counts, which this path adds to. marks: this worker's importance marks (null
  // when no guide is bound).
  // key: the camera sample's own hash, from which the lookup roulette draws (not from the camera path's
  // random numbers, which stay those of nimbus.pt). pixel: the sample's pixel in pixel_radius.
  MergingPath(const MergeContext &mc, RadiusHistogram &lookup_radii, CameraTally &tally,
              ImportanceMarks *marks, const ImportanceMap &importance, uint64_t key,
              PixelRadius &pixel_radius, size_t pixel)
      : mc_(mc),
        radii_(lookup_radii),
        tally_(tally),
        marks_(marks),
        importance_(importance),
        pixel_radius_(pixel_radius),
        pixel_(pixel),
        key_(key) {}
  ~MergingPath() {
    if (mis_.clamped) ++tally_.mis_clamped;
  }
  MergingPath(const MergingPath &) = delete;
  MergingPath &operator=(const MergingPath &) = delete;

  void arrive(float t, const nimbus_interaction_t &ix, const Vec3f &dir) {
    const float c_in = std::abs(dot(Vec3f::load(ix.ng), dir));
    // x_1 seen from the lens, for the splat technique's camera density there.
    if (length_ == 0) cos_first_ = c_in, axis_cos_ = dot(mc_.view_axis, dir);
    length_ += t;
    mis_.arrive(c_in);
  }

  sdk::PathWeight hit(const sdk::LightHit &h) const {
    const float nee_ratio = h.specular ? 0.0f : mis(h.light_pdf / h.bsdf_pdf);
    // No merge technique for this path (no live camera term, as on every path without a sharp vertex):
    // the merges' sum is empty and the emission density, a host call and a loop over the aims, unused.
    const bool eligible = mis_.eligible(h.segments);
    const float lp = eligible ? hit_lp(*mc_.emitters, h) : 0.0f;
    Mis lt = 0;
    if (h.segments >= 3 && mis_.lt > 0) {  // light paths leave direct light to path tracing
      const float lp_lt = mc_.lt_emission->lp(*mc_.emitters, h.light, h.p, h.n, h.wo, h.time);
      if (lp_lt > 0) lt = mis_.lt_times(mis(Mis(lp_lt)), false);
    }
    const float w = hit_weight(nee_ratio, mis_.s_cam(h.segments), lp, mis_.clamped, lt);
    const float without =
        lt > 0 ? ratio_without(w, hit_weight(nee_ratio, mis_.s_cam(h.segments), lp, mis_.clamped)) : 1.0f;
    return {w, lp > 0 && eligible, without};
  }

  void vertex(const sdk::PathVertex &v, CausticsRecord &rec) {
    tally_.work += 2 * kRayWork;  // the ray that found the vertex and its shadow ray
    const bool rough = !is_sharp(mc_.bsdf, mc_.host, *v.ix, v.lobes);
    lookup_ = mis_.append(rough);
    const LookupClass cls = lookup_class(mis_.rough_count);
    q_ = mc_.lookup_probability[cls];
    q_mis_ = mc_.lookup_mis_density(mis_.rough_count);
    if (lookup_) {
      // Photons of similar time only (spec 7.1): the window's share of photon times scales the merge
      // density like the lookup probability does.
      window_ = mc_.clock.window(v.time_u, mc_.time_half_width);
      neff_ = effective_photons(mc_, Vec3f::load(v.ix->p)) * window_.rho;
    }
    eta_splat_ = 0;
    if (lookup_ && v.segments == 1 && (mc_.splat_paths > 0 || mc_.lt_paths > 0)) {
      const double c1 = camera_density(length_, cos_first_, axis_cos_, mc_.theta_pix);
      eta_splat_ = mc_.splat_paths > 0 ? splat_eta(mc_.splat_paths, c1) : 0.0;
      // The light-tracing technique connects rough first vertices (light_paths.hpp).
      mis_.lt_first = mc_.lt_paths > 0 ? mis(splat_eta(mc_.lt_paths, c1)) : 0.0;
    }
    if (lookup_ && cls == kFirstLookup) {
      const float r = merge_radius(mc_.radius_per_length, length_, mc_.scene_radius);
      radius_ = pixel_radius_.radius(pixel_, r, neff_);
      shrunk_ = radius_ < r;
    }
    // A photon has at least 2 vertices (a sharp one and x_s): paths of >= segments + 2 segments.
    if (lookup_ && v.segments + 2 <= mc_.max_depth &&
        (q_ >= 1 || float(mix64(key_ ^ v.segments) >> 40) * 0x1p-24f < q_)) {
      radii_.add(radius_);
      const LookupCost c = merge_photons(mc_, *v.ix, v.wo, v.beta, mis_, radius_, v.segments,
                                         mis_.rough_count, neff_, window_, v.lambda, mis(eta_splat_), rec);
      tally_.lookup_work[cls] += c.work();
      rec.lookup_moment[cls] += q_ * c.light * c.light;
      if (cls == kFirstLookup) {
        pixel_radius_.found(pixel_, c.density_count, radius_, neff_);
        ++tally_.first_lookups, tally_.shrunk_lookups += shrunk_ ? 1 : 0;
      }
      // A lookup that found light marks where the camera needs photons (spec 6.3).
      if (marks_ && c.light > 0)
        marks_->add(importance_.grid(), Vec3f::load(v.ix->p), radius_, importance_.importance(length_));
    }
  }

  sdk::PathWeight nee(const sdk::LightSample &s) const {
    const nimbus_light_incident_t &ls = *s.ls;
    const bool infinite = ls.flags & NIMBUS_LIGHT_INFINITE;
    const float hit_ratio = s.delta ? 0.0f : mis(s.bsdf_pdf / s.light_pdf);
    const bool eligible = mis_.eligible(s.segments);  // as in hit()
    const float lp = eligible ? nee_lp(*mc_.emitters, s) : 0.0f;
    const float cos_j = std::abs(dot(Vec3f::load(s.ix->ng), s.wi));
    const float d2 = infinite ? 1.0f : ls.dist * ls.dist;
    float nk = s.pmf;  // delta lights
    if (!s.delta) nk = infinite ? s.light_pdf : s.light_pdf * std::abs(dot(Vec3f::load(ls.n), s.wi)) / d2;
    Mis lt = 0;
    if (s.segments >= 3 && mis_.lt > 0) {  // light paths leave direct light to path tracing
      const float lp_lt =
          mc_.lt_emission->lp(*mc_.emitters, s.light, Vec3f::load(ls.p), Vec3f::load(ls.n), -s.wi, s.time);
      if (lp_lt > 0)
        lt = mis_.lt_times(mis(Mis(s.bsdf_pdf_rev)) * mis(Mis(lp_lt) * (cos_j / d2) / nk), false);
    }
    const float w =
        nee_weight(hit_ratio, s.bsdf_pdf_rev, mis_.s_cam(s.segments), lp, cos_j / d2, nk, mis_.clamped, lt);
    const float without = lt > 0
                              ? ratio_without(w, nee_weight(hit_ratio, s.bsdf_pdf_rev, mis_.s_cam(s.segments),
                                                            lp, cos_j / d2, nk, mis_.clamped))
                              : 1.0f;
    return {w, lp > 0 && eligible, without};
  }

  void scatter(const nimbus_interaction_t &ix, const Vec3f &wi, const nimbus_bsdf_sample_t &bs,
               uint32_t segments) {
    const bool lt = segments == 1 && !has(bs.lobe, NIMBUS_LOBE_SPECULAR);
    mis_.scatter(std::abs(dot(Vec3f::load(ix.ng), wi)), bs.pdf, bs.pdf_rev, lookup_, segments,
                 kPi * Mis(radius_) * radius_ * Mis(neff_) * q_mis_, eta_splat_, lt ? mis_.lt_first : 0.0);
  }

 private:
  // A contribution's weight without light paths over its weight with them (1 where that is undefined).
  static float ratio_without(float with, float without) { return with > 0 ? without / with : 1.0f; }

  const MergeContext &mc_;
  RadiusHistogram &radii_;  // this worker's lookup radii
  CameraTally &tally_;
  ImportanceMarks *marks_;
  const ImportanceMap &importance_;  // the render's map: its grid and importance rule for marks
  PixelRadius &pixel_radius_;
  size_t pixel_;
  CameraMis mis_;
  float radius_ = 0;     // r_a: fixed at the first rough vertex, used by every lookup (spec 3.5)
  bool shrunk_ = false;  // r_a is below the schedule's radius (pixel_radius.hpp)
  uint64_t key_;         // the lookup roulette's draws: hashes of it and the vertex
  float q_ = 1;          // lookup probability at the current vertex (the merges count 1/q times)
  Mis q_mis_ = 1;        // the merge density's factor in MIS there (MergeContext::lookup_mis_density)
  float neff_ = 0;       // effective photon count at the current lookup vertex (times window_.rho)
  TimeWindow window_;    // the photon times the current lookup accepts
  float length_ = 0;     // path length from the lens to the current vertex
  float cos_first_ = 0, axis_cos_ = 0;  // at x_1: |cos| to the normal, cos to the view axis
  Mis eta_splat_ = 0;                   // splat_eta at the current vertex (x_1 only)
  bool lookup_ = false;                 // the current vertex looks photons up
};

// The plain path (nimbus.pt's estimator: its weights, its image) of camera passes without a photon map
// while the `caustics` element is requested. It classifies the path's vertices as MergingPath does, so
// the element holds the light of paths that have an eligible merge technique whether or not a map is
// active (spec 8: a property of the path, not of the photon schedule).
class ClassifyingPath : public sdk::PlainPath {
 public:
  ClassifyingPath(const EmitterSet &emitters, const nimbus_host_bsdf_v1_t *bsdf, const nimbus_host_t *h)
      : emitters_(emitters), bsdf_(bsdf), h_(h) {}

  sdk::PathWeight hit(const sdk::LightHit &h) const {
    sdk::PathWeight w = PlainPath::hit(h);
    w.divert = mis_.eligible(h.segments) && hit_lp(emitters_, h) > 0;
    return w;
  }
  void vertex(const sdk::PathVertex &v, CausticsRecord &) {
    lookup_ = mis_.append(!is_sharp(bsdf_, h_, *v.ix, v.lobes));
  }
  sdk::PathWeight nee(const sdk::LightSample &s) const {
    sdk::PathWeight w = PlainPath::nee(s);
    w.divert = mis_.eligible(s.segments) && nee_lp(emitters_, s) > 0;
    return w;
  }
  // Only the terms' eligibility is read: the MIS values stay 1.
  void scatter(const nimbus_interaction_t &, const Vec3f &, const nimbus_bsdf_sample_t &, uint32_t segments) {
    mis_.scatter(1, 1, 1, lookup_, segments, 1);
  }

 private:
  const EmitterSet &emitters_;
  const nimbus_host_bsdf_v1_t *bsdf_;
  const nimbus_host_t *h_;
  CameraMis mis_;
  bool lookup_ = false;
};

}  // namespace nimbus::caustics
