// Synthetic paths for the MIS tests (solver spec 10 ii): random vertex classes, pdfs, cosines, distances,
// lights, lookup probabilities and guiding importance, and the closed-form weights q_t^2 / sum_u q_u^2
// built from explicit products of the area-measure pseudo-densities (SeeSharp-style, non-recursive).
#pragma once

#include <cmath>
#include <random>
#include <vector>

#include "lookup_roulette.hpp"
#include "mis.hpp"

namespace nimbus::caustics {

enum class VertexKind { Delta, SharpGlossy, Rough };
enum class LightKind { Area, Point, Infinite, Directional };

struct SyntheticPath {
  uint32_t k = 0;                // segments; x_0 lens, x_k emitter
  std::vector<VertexKind> kind;  // x_1 .. x_{k-1} (index j)
  std::vector<double> cos_prev;  // at x_j towards x_{j-1} (j = 1..k; x_k: cos_z for finite lights)
  std::vector<double> cos_next;  // at x_j towards x_{j+1} (j = 0..k-1)
  std::vector<double> d2;        // squared length of segment (x_j, x_{j+1}), j = 0..k-1
  std::vector<double> w_cam;     // omega^C_j: pdf x_{j-1} -> x_j -> x_{j+1} (j = 1..k-1)
  std::vector<double> w_light;   // omega^L_j: pdf x_{j+1} -> x_j -> x_{j-1}
  LightKind light = LightKind::Area;
  double lp = 1;              // emitter product (0: the light emits no such photon)
  double n_omega = 1;         // NEE solid-angle density incl. selection (area, infinite)
  double pmf = 1;             // NEE selection (delta lights)
  double area = 1, neff = 1;  // pi r_a^2 (first rough vertex) and the photon path count
  uint32_t d_photon = kPhotonMaxVertices;
  // Lookup probabilities (lookup_roulette.hpp) at the camera path's first rough vertex and after it.
  double q_first = 1, q_later = 1;
  // Photon guiding (spec 6.3): the importance I at each vertex and c = N_m / (N_u b^), so that the merge
  // at x_s has the effective count neff (1 + c I_s).
  std::vector<double> importance;
  double ratio = 0;
  // The splat technique (photon_splats.hpp): its eta N_u / C_1 at x_1 (0: photons are not splatted).
  double splat = 0;
  // The light-tracing technique (light_paths.hpp): its eta N_lt / C_1 at x_1 (0: off) and lp_lt, its
  // emission density (0 for infinite lights, which emit no light paths).
  double lt = 0, lp_lt = 0;

  bool finite() const { return light == LightKind::Area || light == LightKind::Point; }
  bool hittable() const { return light == LightKind::Area || light == LightKind::Infinite; }
  bool rough(uint32_t j) const { return kind[j] == VertexKind::Rough; }
  bool delta(uint32_t j) const { return kind[j] == VertexKind::Delta; }
  // Receiver geometry of the last segment: cos_{k-1} / d^2, or cos_{k-1} for infinite lights.
  double g_last() const { return finite() ? cos_next[k - 1] / d2[k - 1] : cos_next[k - 1]; }
  // NEE area density of x_k seen from x_{k-1}.
  double nk() const {
    switch (light) {
      case LightKind::Area:
        return n_omega * cos_prev[k] / d2[k - 1];
      case LightKind::Infinite:
        return n_omega;
      default:
        return pmf;
    }
  }
};

inline double log_uniform(std::mt19937_64 &g, double lo, double hi) {
  return std::exp(std::uniform_real_distribution<double>(std::log(lo), std::log(hi))(g));
}

// Pdfs, distances and light products log-uniform over [1/spread, spread]; k up to max_k.
inline SyntheticPath random_path(std::mt19937_64 &g, double spread = 1e3, uint32_t max_k = 12) {
  SyntheticPath p;
  p.k = std::uniform_int_distribution<uint32_t>(2, max_k)(g);
  p.kind.assign(p.k, VertexKind::Rough);
  p.cos_prev.assign(p.k + 1, 1);
  p.cos_next.assign(p.k, 1);
  p.d2.assign(p.k, 1);
  p.w_cam.assign(p.k, 1);
  p.w_light.assign(p.k, 1);
  std::uniform_int_distribution<int> kind(0, 2), light(0, 3);
  p.light = LightKind(light(g));
  for (uint32_t j = 1; j < p.k; ++j) {
    // Bias towards sharp vertices now and then so that long caustic chains occur.
    p.kind[j] = VertexKind(kind(g));
    if (p.kind[j] != VertexKind::Delta) {
      p.w_cam[j] = log_uniform(g, 1 / spread, spread);
      p.w_light[j] = log_uniform(g, 1 / spread, spread);
    }
  }
  for (uint32_t j = 0; j <= p.k; ++j) {
    if (j >= 1) p.cos_prev[j] = log_uniform(g, 1 / spread, 1);
    if (j < p.k) p.cos_next[j] = log_uniform(g, 1 / spread, 1);
    if (j < p.k) p.d2[j] = log_uniform(g, 1 / spread, spread);
  }
  p.lp = std::uniform_real_distribution<double>(0, 1)(g) < 0.1 ? 0.0 : log_uniform(g, 1 / spread, spread);
  p.n_omega = log_uniform(g, 1 / spread, spread);
  p.pmf = log_uniform(g, 1 / spread, 1);
  p.area = log_uniform(g, 1 / spread, spread);
  p.neff = log_uniform(g, 1, 1e6);
  p.d_photon = std::uniform_real_distribution<double>(0, 1)(g) < 0.3
                   ? std::uniform_int_distribution<uint32_t>(2, 6)(g)
                   : kPhotonMaxVertices;
  if (std::uniform_real_distribution<double>(0, 1)(g) < 0.5) {
    p.q_first = log_uniform(g, kMinLookupProbability, 1);
    p.q_later = log_uniform(g, kMinLookupProbability, 1);
  }
  p.importance.assign(p.k, 0);
  if (std::uniform_real_distribution<double>(0, 1)(g) < 0.5) {
    // Importance over many decades, unmarked (0) at a third of the vertices.
    p.ratio = log_uniform(g, 1e-3, 1e3);
    for (uint32_t j = 1; j < p.k; ++j)
      if (std::uniform_real_distribution<double>(0, 1)(g) < 0.67) p.importance[j] = log_uniform(g, 1e-4, 1e4);
  }
  if (std::uniform_real_distribution<double>(0, 1)(g) < 0.5)
    p.splat = log_uniform(g, 1 / spread, spread) * p.neff;
  // Light paths are off for guided maps (importance) and infinite lights.
  if (p.ratio == 0 && std::uniform_real_distribution<double>(0, 1)(g) < 0.6) {
    p.lt = log_uniform(g, 1 / spread, spread) * p.neff;
    p.lp_lt = p.finite() ? log_uniform(g, 1 / spread, spread) : 0.0;
  }
  return p;
}

// ---- closed form --------------------------------------------------------------------------------
struct ClosedForm {
  double qh = 0, qn = 0;
  std::vector<double> qm;  // by s (0 where no technique)
  double qt = 0;           // the splat at x_1: a technique wherever the merge at x_1 is
  double ql = 0;           // the light-tracing technique: k >= 3, x_1 rough and lp_lt > 0
  double sum() const {
    double s = qh * qh + qn * qn + qt * qt + ql * ql;
    for (double q : qm) s += q * q;
    return s;
  }
};

// pi r_s^2 at lookup vertex x_s: every lookup of a path uses its first rough vertex's radius.
inline double area_at(const SyntheticPath &p, uint32_t) { return p.area; }

// The effective photon count of the merge at x_s, as the production code rounds it (a float).
inline double neff_at(const SyntheticPath &p, uint32_t s) {
  return double(float(double(float(p.neff)) * (1.0 + p.ratio * double(float(p.importance[s])))));
}

// The merge density's factor at the rough vertex with `rank` rough vertices up to it (1: the first):
// q_first there, q_later at the second, and kLaterLookupMisFactor less per rough vertex after that.
inline double lookup_factor_at_rank(const SyntheticPath &p, uint32_t rank) {
  if (rank <= 1) return p.q_first;
  double f = p.q_later;
  for (uint32_t n = 2; n < rank; ++n) f *= double(kLaterLookupMisFactor);
  return f;
}
// The same at rough vertex x_s.
inline double lookup_probability_at(const SyntheticPath &p, uint32_t s) {
  uint32_t rank = 0;
  for (uint32_t j = 1; j <= s; ++j) rank += p.rough(j) ? 1 : 0;
  return lookup_factor_at_rank(p, rank);
}

// The merge at s is a technique (E1-E4; lookups at every rough vertex).
inline bool merge_eligible(const SyntheticPath &p, uint32_t s) {
  if (!(p.lp > 0) || s < 1 || s + 2 > p.k || !p.rough(s)) return false;
  if (p.rough(p.k - 1)) return false;  // the photon's first vertex must be sharp
  bool sharp = false;
  for (uint32_t j = s + 1; j < p.k; ++j) {
    sharp = sharp || !p.rough(j);
    if (p.rough(j) && j + 1 < p.k && p.rough(j + 1)) return false;
  }
  return sharp && p.k - s <= p.d_photon;
}

inline ClosedForm closed_form(const SyntheticPath &p) {
  const uint32_t k = p.k;
  // C_j (j = 2..k) and L_j (j = 1..k-2); L_{k-1} L_k = lp * g.
  std::vector<double> C(k + 1, 1), L(k + 1, 1);
  for (uint32_t j = 2; j < k; ++j) C[j] = p.w_cam[j - 1] * p.cos_prev[j] / p.d2[j - 1];
  C[k] = p.light == LightKind::Area ? p.w_cam[k - 1] * p.cos_prev[k] / p.d2[k - 1] : p.w_cam[k - 1];
  for (uint32_t j = 1; j + 2 <= k; ++j) L[j] = p.w_light[j + 1] * p.cos_next[j] / p.d2[j];
  const double light_pair = p.lp * p.g_last();
  ClosedForm f;
  double prod_c = 1;
  for (uint32_t j = 2; j < k; ++j) prod_c *= C[j];
  if (p.hittable()) f.qh = prod_c * C[k];
  if (!p.delta(k - 1)) f.qn = prod_c * p.nk();
  f.qm.assign(k + 1, 0);
  for (uint32_t s = 1; s < k; ++s) {
    if (!merge_eligible(p, s)) continue;
    double q = area_at(p, s) * neff_at(p, s) * lookup_probability_at(p, s);
    for (uint32_t j = 2; j <= s; ++j) q *= C[j];
    for (uint32_t j = s; j + 2 <= k; ++j) q *= L[j];
    f.qm[s] = q * light_pair;
  }
  if (f.qm[1] > 0) f.qt = f.qm[1] * p.splat / (area_at(p, 1) * neff_at(p, 1) * lookup_probability_at(p, 1));
  if (p.lt > 0 && p.lp_lt > 0 && p.rough(1) && k >= 3) {
    f.ql = p.lt * p.lp_lt * p.g_last();
    for (uint32_t j = 1; j + 2 <= k; ++j) f.ql *= L[j];
  }
  return f;
}

}  // namespace nimbus::caustics
