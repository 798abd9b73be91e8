// MIS between path tracing (BSDF hit H, next-event estimation N) and photon merging at camera vertex
// x_s (M_s), evaluated iteratively as in the solver spec (shared/design/caustics-solver.md, section 3.3):
// the photon side carries A (light-side techniques H and N) and B (the merges at the rough photon
// vertices further towards the light), the camera side a list of pending merge terms R (one per earlier
// rough camera vertex that can still be a merge technique).
//
// Lookups happen at every rough camera vertex (spec 3.2 E2 with n_max unlimited, the paper's VCM
// choice): with lookups at the first two only, paths with three or more rough vertices in front of a
// caustic (e.g. pool floor -> wall -> floor -> water -> sun) would have no merge technique at all and
// come from rare BSDF hits of the sun alone, as fireflies.
//
// Merge radius: every lookup of a camera path uses r_a, the radius at its first rough vertex (spec 3.5),
// so the radius ratio between two merges of one path is 1. Wider kernels behind a diffuse bounce did not
// lower the error, which sits in first-vertex merges (docs/performance.md §6).
//
// Every quantity here is already raised to the MIS exponent: mis(x) = x^beta with beta = 2, the power
// heuristic of nimbus.pt, so that paths without an eligible merge get exactly nimbus.pt's weights.
// Russian roulette is excluded on both sides; delta lobes use forward = reverse pdf = 1.
//
// Notation (area-measure pseudo-densities of path x_0 (lens) ... x_k (emitter)): C_j camera side,
// L_j light side, N_k NEE. "lp" = the emitter's photon-side product L_k * L_{k-1} without the receiver's
// geometry term g (g = cos_{k-1} / d^2 for finite emitters, cos_{k-1} for infinite ones):
//   area light      lp = P_sel * P_pos(z) * P_dir(z -> x_{k-1})
//   point/spot      lp = P_sel * P_dir              (the position delta cancels)
//   infinite        lp = P_sel * P_dir(w) * P_pos   (P_pos = 1 / (pi R_e^2) on the emission disk)
//   directional     lp = P_sel * P_pos              (the direction delta cancels)
// These are pure value types (no host calls) so that tests can drive them with synthetic paths.
//
// Range: products of squared pdf ratios over up to 32 vertices overflow float (and, at the extremes,
// double). Both sides keep their values as doubles with a shared power-of-two scale, renormalised as
// they grow or shrink, so ratios stay exact; a photon stores log2 A and log2 B as floats. A weight whose
// competitors overflow even then is 0, the right limit, never inf/inf = NaN. Such weights are noted
// (`clamped`), and the solver counts those paths as a render statistic.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "lookup_roulette.hpp"
#include "mis_scale.hpp"

namespace nimbus::caustics {

// GGX alpha below which a lobe is "sharp" (caustic-forming); spec section 2.
inline constexpr float kSharpAlpha = 0.1f;
// D_photon: most vertices a photon path may have (x_{k-1} ... x_s).
inline constexpr uint32_t kPhotonMaxVertices = 32;
// Pending camera-side merge terms: a term at x_s' can only be a technique for paths with
// k - s' <= D_photon, so at most D_photon + 1 terms are alive at once.
inline constexpr uint32_t kMaxCameraTerms = kPhotonMaxVertices + 1;
// Photon-side state of one photon path (spec 3.3, "photon side").
struct PhotonMis {
  Mis A = 0;  // (q_H + q_N) / q_M,s  times  eta_s / omega^C_s, at the current vertex
  Mis B = 0;  // sum over the stored rough vertices s' further towards the light of
              // q_M,s' / q_M,s, over the same factors except the radius ratio (included); each term
              // times mis(kLaterLookupMisFactor) per rough vertex between s' and the photon's end, whose
              // merge multiplies in the rest of its rank factor (lookup_roulette.hpp)
  // The MIS exponent of kLaterLookupMisFactor: B's decay per rough vertex.
  static constexpr Mis kRankDecay = Mis(kLaterLookupMisFactor) * kLaterLookupMisFactor;
  // Photon guiding (spec 6.3): the merge at s' has the effective photon count N_u (1 + c I(x_s')), so its
  // term in B weighs (1 + c I)^2 = 1 + 2 c I + c^2 I^2 (the MIS exponent). c is known only once the pass
  // is done: these are the same sum as B with each term times I and times I^2.
  Mis B_importance = 0, B_importance2 = 0;
  int exp2 = 0;          // A, B, B_importance and B_importance2 are each times 2^exp2
  bool b_valid = false;  // some stored rough vertex precedes (B is a sum of >= 1 terms)

  float log2_A() const { return stored_log2(A, exp2); }
  float log2_B() const { return stored_log2(B, exp2); }
  float log2_B_importance() const { return stored_log2(B_importance, exp2); }
  float log2_B_importance2() const { return stored_log2(B_importance2, exp2); }

  // The state's values: A, B, B_importance, B_importance2.
  auto value() {
    return [this](uint32_t i) -> Mis & {
      return i == 0 ? A : i == 1 ? B : i == 2 ? B_importance : B_importance2;
    };
  }

  // Emission. hittable: BSDF sampling can hit the emitter (area and non-delta infinite lights).
  // cos_e: |cos| at the emitter between its normal and the photon direction (1 for infinite lights).
  void emit(bool hittable, float cos_e, float lp) {
    A = hittable && lp > 0 ? mis(Mis(cos_e) / lp) : 0.0;
    B = B_importance = B_importance2 = 0;
    exp2 = 0;
    b_valid = false;
    rescale();
  }
  // Arrival at a vertex; c_in = |cos| there between the geometric normal and the arriving segment.
  void arrive(float c_in) {
    const Mis m = mis(Mis(c_in));
    A /= m;
    B /= m;
    B_importance /= m;
    B_importance2 /= m;
    rescale();
  }
  // Scattering at the current vertex: c_out = |cos| of the new direction, w_fwd its pdf, w_rev the pdf
  // of the reverse direction (what a camera path would use). E: NEE term of the first vertex (below), 0
  // elsewhere. rough / stored: the vertex's class and whether a photon was stored at it (then the merge
  // there is a technique for every longer path through it). importance: I at the stored vertex.
  // A rough vertex lies between every earlier stored vertex and any later merge: their terms take one
  // more rank factor (kRankDecay).
  void scatter(float c_out, float w_fwd, float w_rev, bool rough, bool stored, Mis E, float importance = 0) {
    const Mis g = mis(Mis(c_out) / w_fwd), r = mis(Mis(w_rev));
    const Mis rb = rough ? r * kRankDecay : r;
    A *= r;
    B *= rb;
    B_importance *= rb;
    B_importance2 *= rb;
    if (E > 0) {
      const Mis t = scaled_term(E, 4, value(), exp2);
      A += t;
    }
    if (rough && stored) {
      const Mis t = scaled_term(1.0, 4, value(), exp2);
      B += t;
      const Mis I = importance;
      if (I > 0) {
        const Mis t1 = scaled_term(I, 4, value(), exp2);
        B_importance += t1;
        const Mis t2 = scaled_term(I * I, 4, value(), exp2);
        B_importance2 += t2;
      }
      b_valid = true;
    }
    A *= g;
    B *= g;
    B_importance *= g;
    B_importance2 *= g;
    rescale();
  }
  void rescale() { renormalise(4, value(), exp2); }
};

// log2 of B with every term at its vertex's effective photon count relative to N_u, squared (the MIS
// exponent), from a photon's log2 B, B_importance and B_importance2:
// log2(B + 2 c B_importance + c^2 B_importance2), c = N_m / (N_u b^) of the pass (spec 6.3). Exact in
// double over the whole float range: every term is scaled by the largest.
inline float fold_importance(float log2_b, float log2_b1, float log2_b2, double c) {
  constexpr float kNone = -std::numeric_limits<float>::infinity();
  if (!(c > 0) || (log2_b1 == kNone && log2_b2 == kNone)) return log2_b;
  const double l2c = std::log2(c);
  const double x[3] = {double(log2_b), double(log2_b1) + 1 + l2c, double(log2_b2) + 2 * l2c};
  const double m = std::max({x[0], x[1], x[2]});
  return float(m + std::log2(std::exp2(x[0] - m) + std::exp2(x[1] - m) + std::exp2(x[2] - m)));
}

// The NEE term E of the first photon vertex x_{k-1} (after arrive()): N_k / (L_k L_{k-1}).
// nk: the NEE area density of x_k seen from x_{k-1} including light selection (area lights:
// pmf * pdf_incident * cos_z / d^2; delta positions: pmf; infinite: pmf * pdf_incident; directional:
// pmf). d2: squared distance to the emitter (1 for infinite lights). c_in as in arrive().
inline Mis photon_nee_term(bool nee_possible, float nk, float d2, float lp, float c_in) {
  return nee_possible && lp > 0 ? mis(Mis(nk) * d2 / (Mis(lp) * c_in)) : 0.0;
}

// One pending camera-side merge term (a merge technique at camera vertex s). No default member
// initialisers: a camera path's CameraMis leaves its unused terms uninitialised instead of zeroing 660
// bytes per path.
struct CameraTerm {
  Mis R;
  uint32_t s;       // the camera vertex index that created it
  bool has_sharp;   // a sharp vertex after x_s
  bool last_rough;  // the last appended vertex was rough
  bool dead;        // two adjacent rough vertices after x_s: no merge at s for longer paths
};

// Camera-side state of one camera path (spec 3.3, "camera side").
struct CameraMis {
  CameraTerm terms[kMaxCameraTerms];  // [0, n_terms) in use
  uint32_t n_terms = 0;
  uint32_t rough_count = 0;                // rough vertices among x_1 .. x_j (after append)
  uint32_t d_photon = kPhotonMaxVertices;  // the photon tracer's D_photon (tests vary it)
  int exp2 = 0;                            // every R is terms[i].R * 2^exp2
  // The light-tracing technique (light_paths.hpp), eligible for paths of three or more segments once
  // x_1 scattered non-deltaly: its R (times 2^exp2), and before that x_1's mis(eta_lt) (unscaled), which
  // merges at x_1 read. Its emission density lp_lt is its own, so it is summed apart from the merge terms.
  Mis lt = 0, lt_first = 0;
  mutable bool clamped = false;  // a weight's competitors overflowed (see the top)

  // The state's values: the terms in use, then lt.
  auto value() {
    return [this](uint32_t i) -> Mis & { return i < n_terms ? terms[i].R : lt; };
  }

  // Arrival at x_{j+1}: c_in = |cos| at it. Not called for escaped rays (infinite lights).
  void arrive(float c_in) {
    const Mis m = mis(Mis(c_in));
    for (uint32_t i = 0; i < n_terms; ++i) terms[i].R /= m;
    lt /= m;
    rescale();
  }
  // Appends the class of the scattering vertex just reached. Returns true when it is a lookup vertex
  // (rough: E1 + E2, lookups at every rough vertex).
  bool append(bool rough) {
    for (uint32_t i = 0; i < n_terms; ++i) {
      CameraTerm &t = terms[i];
      if (!rough) {
        t.has_sharp = true;
        t.last_rough = false;
      } else if (t.last_rough) {
        t.dead = true;
      } else {
        t.last_rough = true;
      }
    }
    if (!rough) return false;
    ++rough_count;
    return true;
  }
  // Scattering at x_j: c_out, w_fwd, w_rev as in PhotonMis::scatter. lookup: x_j is a lookup vertex
  // (then a new term starts with eta_j = pi r_j^2 * Neff(x_j) * rho(x_j)). eta_splat: at x_1, the splat
  // technique's eta (splat_eta; 0 without one), which samples the same paths as the merge there. Terms
  // that can no longer be merge techniques (dead, or too far from any later emitter for D_photon) are
  // dropped first. eta_lt: at x_1 scattering non-deltaly, mis(eta_lt) of the light-tracing technique.
  void scatter(float c_out, float w_fwd, float w_rev, bool lookup, uint32_t j, Mis eta, Mis eta_splat = 0,
               Mis eta_lt = 0) {
    const Mis g = mis(Mis(c_out) / w_fwd);
    const Mis r = mis(Mis(w_rev));
    uint32_t n = 0;
    for (uint32_t i = 0; i < n_terms; ++i) {
      CameraTerm t = terms[i];
      if (t.dead || j + 1 - t.s > d_photon) continue;  // later paths have k >= j + 1
      t.R *= g * r;
      terms[n++] = t;
    }
    n_terms = n;
    lt *= g * r;
    if (lookup && n_terms < kMaxCameraTerms) {
      const Mis R = scaled_term(g * (mis(eta) + mis(eta_splat)), n_terms + 1, value(), exp2);
      terms[n_terms++] = CameraTerm{R, j, false, false, false};
    }
    if (eta_lt > 0) {
      const Mis t = scaled_term(g * eta_lt, n_terms + 1, value(), exp2);
      lt += t;
    }
    rescale();
  }
  void rescale() { renormalise(n_terms + 1, value(), exp2); }
  // The light-tracing technique's competitor value at a path end where the camera side alone supplies
  // the rest of the ratio `factor` (times mis(lp_lt) and the light side's factors): x_1's eta before its
  // scatter when the path ends there (first), else R.
  Mis lt_times(Mis factor, bool first) const {
    if (first) return lt_first * factor;
    const Mis v = scaled_product(lt, factor, exp2);
    if (!(v <= std::numeric_limits<Mis>::max())) clamped = true;
    return v;
  }
  // S_cam: sum of R over the merge techniques eligible for a path of k segments that ends here (an
  // emitter hit at x_k, or NEE from x_{k-1}): E3 on the camera vertices after s, and x_{k-1} (the last
  // vertex appended, the photon's first) sharp: the photon tracer ends paths whose first vertex is rough.
  MisSum s_cam(uint32_t k) const {
    MisSum s{0, exp2};
    for (uint32_t i = 0; i < n_terms; ++i)
      if (live(terms[i], k)) s.sum += terms[i].R;
    return s;
  }
  // Whether any merge technique is eligible for a path of k segments ending here (caustics element).
  bool eligible(uint32_t k) const {
    for (uint32_t i = 0; i < n_terms; ++i)
      if (live(terms[i], k)) return true;
    return false;
  }
  bool live(const CameraTerm &t, uint32_t k) const {
    return t.has_sharp && !t.dead && !t.last_rough && k - t.s <= d_photon;
  }
  // Sum of R over the terms that stay merge techniques when a photon of depth k - s completes the path
  // at the current lookup vertex x_s (after append): the photon supplies the sharp vertex.
  MisSum gamma_sum(uint32_t k) const {
    MisSum s{0, exp2};
    for (uint32_t i = 0; i < n_terms; ++i) {
      const CameraTerm &t = terms[i];
      if (!t.dead && k - t.s <= d_photon) s.sum += t.R;
    }
    return s;
  }
};

// Balance of the weights. `others` is finite unless it overflowed (weight 0: the right limit) or an input pdf
// was NaN (then the technique gets weight 0).
inline float mis_weight(Mis others) {
  const Mis w = 1.0 / (1.0 + others);
  return w >= 0 && w <= 1 ? float(w) : 0.0f;
}

// Weight of NEE from x_j to an emitter point (spec 3.3).
//   hit_ratio:  q_H / q_N  = mis(omega^C_j(-> z) / n_omega) for hittable emitters (area, infinite
//               non-delta), 0 for delta lights (computed by the caller: it is nimbus.pt's ratio)
//   w_rev:      omega^L_j(z ->): pdf of scattering from the light's direction back to x_{j-1}
//   s_cam:      CameraMis::s_cam(j + 1) after appending x_j
//   lp, g, nk:  emitter product, receiver geometry (cos_j / d^2, or cos_j), NEE area density
//   lt:         the light-tracing technique's ratio (CameraMis::lt_times; 0 without it)
inline float nee_weight(float hit_ratio, float w_rev, const MisSum &s_cam, float lp, float g, float nk,
                        bool &clamped, Mis lt = 0) {
  Mis merges = 0;
  if (s_cam.sum > 0 && lp > 0) merges = s_cam.times(mis(Mis(w_rev)) * mis(Mis(lp) * g / nk), clamped);
  return mis_weight(hit_ratio + merges + lt);
}

// Weight of a BSDF-sampled emitter hit. nee_ratio = q_N / q_H (nimbus.pt's ratio; 0 when NEE could not
// have sampled it); s_cam after arrival (finite emitters) or after the scatter (infinite ones).
inline float hit_weight(float nee_ratio, const MisSum &s_cam, float lp, bool &clamped, Mis lt = 0) {
  Mis merges = 0;
  if (s_cam.sum > 0 && lp > 0) merges = s_cam.times(mis(Mis(lp)), clamped);
  return mis_weight(nee_ratio + merges + lt);
}

// Weight of merging photon (A, B, b_valid, prev_rough, depth) at lookup vertex x_s.
//   w_cam_fwd:  omega^C_s(w_p): pdf that the camera path at x_s samples the photon's incoming direction
//   w_cam_rev:  omega^L_s(w_p -> x_{s-1}): the reverse pdf of the same pair
//   eta:        mis(pi r_s^2 * Neff_s * rho_s); neff: mis(Neff_s * rho_s); neff_b: mis(Neff at B's
//               vertices) (v1: Neff is the same everywhere)
//   gamma_sum:  CameraMis::gamma_sum(s + depth) (its terms carry their own eta)
//   eta_splat:  at x_1, mis(splat_eta) of the splat technique (0 elsewhere and without one)
//   lt:         the light-tracing technique's ratio to the merge times eta (0 without it)
inline float merge_weight(float log2_A, float log2_B, bool b_valid, bool prev_rough, float w_cam_fwd,
                          float w_cam_rev, Mis eta, Mis neff, Mis neff_b, const MisSum &gamma_sum,
                          bool &clamped, Mis eta_splat = 0, Mis lt = 0) {
  Mis light = std::exp2(Mis(log2_A)) / eta;
  if (b_valid) light += std::exp2(Mis(log2_B)) * neff_b / neff;
  Mis others = mis(Mis(w_cam_fwd)) * light + (eta_splat > 0 || lt > 0 ? (eta_splat + lt) / eta : 0.0);
  if (!(others <= std::numeric_limits<Mis>::max())) clamped = true;
  if (!prev_rough && gamma_sum.sum > 0) others += gamma_sum.times(mis(Mis(w_cam_rev)) / eta, clamped);
  return mis_weight(others);
}

// The splat technique (photon_splats.hpp): a stored photon connected to the camera as the path's first
// vertex x_1, as a light tracer would. It samples the paths the merge at x_1 samples, with N_u light
// paths against the merge's pi r^2 Neff rho per camera path, so its eta is N_u / C_1 (C_1: the camera
// paths' density of first vertices at x_1, camera_density) and every ratio to the other techniques is
// the merge at x_1's times eta_splat / eta.
inline Mis splat_eta(double photon_paths, double camera_density) {
  return camera_density > 0 ? photon_paths / camera_density : 0.0;
}
// The camera paths' density of first vertices at x_1 per iteration, in area measure: one sample per
// pixel, a pixel of theta_pix^2 cos^3(axis angle) steradians at the lens, times cos_1 / d^2. Both sides
// evaluate it from the same quantities of the path (distance, cosine at x_1, cosine to the view axis),
// so the weights stay a partition of unity whatever it misses of the camera model.
inline double camera_density(float d, float cos_1, float cos_axis, float theta_pix) {
  const double c = std::abs(double(cos_axis)), px = double(theta_pix) * theta_pix;
  return d > 0 && c > 0 && px > 0 ? std::abs(double(cos_1)) / (double(d) * d * px * c * c * c) : 0.0;
}
// Weight of splatting photon (A, B, b_valid) at x_1: the merge at x_1 and every technique that merge
// competes with (its arguments as merge_weight's), relative to the splat's eta_splat = mis(splat_eta).
// lt: the light-tracing technique's ratio to the merge at x_1 times eta (0 without it).
inline float splat_weight(float log2_A, float log2_B, bool b_valid, float w_cam_fwd, Mis eta, Mis neff,
                          Mis neff_b, Mis eta_splat, bool &clamped, Mis lt = 0) {
  if (!(eta_splat > 0)) return 0.0f;
  Mis light = std::exp2(Mis(log2_A));
  if (b_valid && neff > 0) light += std::exp2(Mis(log2_B)) * neff_b * eta / neff;
  const Mis others = (eta + mis(Mis(w_cam_fwd)) * light + lt) / eta_splat;
  if (!(others <= std::numeric_limits<Mis>::max())) clamped = true;
  return mis_weight(others);
}

}  // namespace nimbus::caustics
