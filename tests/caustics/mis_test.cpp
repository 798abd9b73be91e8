// MIS partition of unity (solver spec 10 ii): synthetic paths with random vertex classes, pdfs, cosines
// and distances drive the production photon-side and camera-side state machines (mis.hpp) exactly as
// the plugin does; every weight they give must equal the closed form q_t^2 / sum_u q_u^2 built from
// explicit products of the area-measure pseudo-densities, and the weights must sum to one.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "lookup_roulette.hpp"
#include "mis.hpp"

namespace nimbus::caustics {
namespace {

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

double log_uniform(std::mt19937_64 &g, double lo, double hi) {
  return std::exp(std::uniform_real_distribution<double>(std::log(lo), std::log(hi))(g));
}

// Pdfs, distances and light products log-uniform over [1/spread, spread]; k up to max_k.
SyntheticPath random_path(std::mt19937_64 &g, double spread = 1e3, uint32_t max_k = 12) {
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
  return p;
}

// ---- closed form --------------------------------------------------------------------------------
struct ClosedForm {
  double qh = 0, qn = 0;
  std::vector<double> qm;  // by s (0 where no technique)
  double sum() const {
    double s = qh * qh + qn * qn;
    for (double q : qm) s += q * q;
    return s;
  }
};

// pi r_s^2 at lookup vertex x_s: every lookup of a path uses its first rough vertex's radius.
double area_at(const SyntheticPath &p, uint32_t) { return p.area; }

// The effective photon count of the merge at x_s, as the production code rounds it (a float).
double neff_at(const SyntheticPath &p, uint32_t s) {
  return double(float(double(float(p.neff)) * (1.0 + p.ratio * double(float(p.importance[s])))));
}

// The lookup probability at rough vertex x_s: q_first at the path's first rough vertex.
double lookup_probability_at(const SyntheticPath &p, uint32_t s) {
  for (uint32_t j = 1; j < s; ++j)
    if (p.rough(j)) return p.q_later;
  return p.q_first;
}

// The merge at s is a technique (E1-E4; lookups at every rough vertex).
bool merge_eligible(const SyntheticPath &p, uint32_t s) {
  if (!(p.lp > 0) || s < 1 || s + 2 > p.k || !p.rough(s)) return false;
  if (p.rough(p.k - 1)) return false;  // the photon's first vertex must be sharp
  bool sharp = false;
  for (uint32_t j = s + 1; j < p.k; ++j) {
    sharp = sharp || !p.rough(j);
    if (p.rough(j) && j + 1 < p.k && p.rough(j + 1)) return false;
  }
  return sharp && p.k - s <= p.d_photon;
}

ClosedForm closed_form(const SyntheticPath &p) {
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
  return f;
}

// ---- production state machines --------------------------------------------------------------------
struct PhotonAt {
  bool stored = false;
  float A = 0, B = 0;  // log2 A, log2 B (B with its vertices' effective counts folded in)
  bool b_valid = false, prev_rough = false;
};

struct Weights {
  double wh = 0, wn = 0;
  std::vector<double> wm;
  bool hit = false, nee = false;
  std::vector<bool> merged;
  bool clamped = false;   // a weight's competitors overflowed double
  bool rescaled = false;  // a state left [2^-400, 2^400] (float would have overflowed long before)
};

Weights production(const SyntheticPath &p) {
  const uint32_t k = p.k;
  const float lp = float(p.lp);
  // Photon side: from the emitter towards the camera, as trace_photon does.
  std::vector<PhotonAt> at(k + 1);
  PhotonMis pm;
  pm.emit(p.hittable(), p.light == LightKind::Area ? float(p.cos_prev[k]) : 1.0f, lp);
  bool had_sharp = false, prev_rough = false, rescaled = false;
  for (uint32_t j = k - 1; j >= 1; --j) {
    const float c_in = float(p.cos_next[j]);
    pm.arrive(c_in);
    const bool rough = p.rough(j);
    Mis E = 0;
    if (j == k - 1 && !p.delta(j)) {
      const float d2 = p.finite() ? float(p.d2[k - 1]) : 1.0f;
      const float nk = float(p.nk());
      E = photon_nee_term(true, nk, d2, lp, c_in);
    }
    if (rough && j == k - 1) break;  // a path whose first vertex is rough ends there
    const bool stored = rough && had_sharp && (k - j) <= p.d_photon;
    at[j] = PhotonAt{stored, pm.log2_A(),
                     fold_importance(pm.log2_B(), pm.log2_B_importance(), pm.log2_B_importance2(), p.ratio),
                     pm.b_valid, prev_rough};
    if (rough && prev_rough) break;
    pm.scatter(float(p.cos_prev[j]), float(p.w_light[j]), float(p.w_cam[j]), rough, stored, E,
               float(p.importance[j]));
    rescaled = rescaled || pm.exp2 != 0;
    prev_rough = rough;
    had_sharp = had_sharp || !rough;
  }
  // Camera side, as trace_pixel<true> does.
  Weights w;
  w.rescaled = rescaled;
  w.wm.assign(k + 1, 0);
  w.merged.assign(k + 1, false);
  CameraMis cm;
  cm.d_photon = p.d_photon;
  Mis area = 0;  // pi r_j^2 of the current lookup vertex
  const Mis neff = Mis(float(p.neff));
  for (uint32_t j = 1; j <= k; ++j) {
    if (j >= 2 && !(j == k && !p.finite())) cm.arrive(j == k ? float(p.cos_prev[k]) : float(p.cos_prev[j]));
    if (j == k) {
      if (p.hittable()) {
        const float nee_ratio = p.delta(k - 1) ? 0.0f : mis(float(p.n_omega / p.w_cam[k - 1]));
        w.wh = hit_weight(nee_ratio, cm.s_cam(k), lp, cm.clamped);
        w.hit = true;
      }
      break;
    }
    const bool lookup = cm.append(p.rough(j));
    // The plugin's radius: r_a, fixed at the first rough vertex; its lookup probability by class.
    if (lookup && cm.rough_count == 1) area = Mis(float(p.area));
    const Mis q = Mis(float(lookup_class(cm.rough_count) == kFirstLookup ? p.q_first : p.q_later));
    const Mis q_b = Mis(float(p.q_later));
    // The production code's effective count at a lookup vertex: N_u (1 + c I) in double, as a float.
    const Mis neff_j = Mis(float(double(neff) * (1.0 + p.ratio * double(float(p.importance[j])))));
    if (lookup && at[j].stored && p.lp > 0) {
      const PhotonAt &ph = at[j];
      w.wm[j] =
          merge_weight(ph.A, ph.B, ph.b_valid, ph.prev_rough, float(p.w_cam[j]), float(p.w_light[j]),
                       mis(area * neff_j * q), mis(neff_j * q), mis(neff * q_b), cm.gamma_sum(k), cm.clamped);
      w.merged[j] = true;
    }
    if (j == k - 1 && !p.delta(j)) {
      const float hit_ratio = p.hittable() ? mis(float(p.w_cam[j] / p.n_omega)) : 0.0f;
      w.wn = nee_weight(hit_ratio, float(p.w_light[j]), cm.s_cam(k), lp, float(p.g_last()), float(p.nk()),
                        cm.clamped);
      w.nee = true;
    }
    cm.scatter(float(p.cos_next[j]), float(p.w_cam[j]), float(p.w_light[j]), lookup, j, area * neff_j * q);
  }
  w.clamped = cm.clamped;
  w.rescaled = w.rescaled || cm.exp2 != 0;
  return w;
}

// Relative agreement, with an absolute floor for weights near zero.
void expect_weight(double got, double want, const char *what, int path) {
  EXPECT_NEAR(got, want, 2e-3 * std::max(want, 1e-2)) << what << " on path " << path;
}

TEST(CausticsMis, WeightsMatchClosedFormAndSumToOne) {
  std::mt19937_64 g(20190704);
  int paths_with_merges = 0, long_chains = 0;
  for (int n = 0; n < 200000; ++n) {
    const SyntheticPath p = random_path(g);
    const ClosedForm f = closed_form(p);
    const double total = f.sum();
    if (!(total > 0) || !std::isfinite(total)) continue;
    const Weights w = production(p);
    double sum = 0;
    if (w.hit) {
      expect_weight(w.wh, f.qh * f.qh / total, "hit", n);
      sum += w.wh;
    } else {
      EXPECT_EQ(f.qh, 0) << "hit technique missing on path " << n;
    }
    if (w.nee) {
      expect_weight(w.wn, f.qn * f.qn / total, "nee", n);
      sum += w.wn;
    } else {
      EXPECT_EQ(f.qn, 0) << "nee technique missing on path " << n;
    }
    bool any_merge = false;
    for (uint32_t s = 1; s < p.k; ++s) {
      // The production code merges exactly where the closed form has a technique.
      EXPECT_EQ(w.merged[s], f.qm[s] > 0) << "merge eligibility at s = " << s << " on path " << n;
      if (!w.merged[s]) continue;
      any_merge = true;
      expect_weight(w.wm[s], f.qm[s] * f.qm[s] / total, "merge", n);
      sum += w.wm[s];
    }
    paths_with_merges += any_merge;
    long_chains += any_merge && p.k >= 8;
    EXPECT_NEAR(sum, 1.0, 1e-3) << "path " << n;
    if (HasFailure()) return;
  }
  std::printf("paths with merge techniques: %d (k >= 8: %d)\n", paths_with_merges, long_chains);
  EXPECT_GT(paths_with_merges, 10000);
  EXPECT_GT(long_chains, 500);
}

// Paths of up to 40 segments with pdfs, cosines and distances over 24 decades: the products overflow
// float and double. Every weight stays in [0, 1] and they sum to 1 within float precision: the states'
// shared scales keep every ratio; a weight whose competitors overflow double is 0, the right limit.
TEST(CausticsMis, ExtremePathsKeepWeightsInRange) {
  std::mt19937_64 g(7);
  int saturated = 0, rescaled = 0, checked = 0;
  for (int n = 0; n < 50000; ++n) {
    const SyntheticPath p = random_path(g, 1e12, 40);
    const Weights w = production(p);
    double sum = (w.hit ? w.wh : 0.0) + (w.nee ? w.wn : 0.0);
    for (uint32_t s = 1; s < p.k; ++s) {
      if (!w.merged[s]) continue;
      ASSERT_TRUE(w.wm[s] >= 0 && w.wm[s] <= 1) << "merge weight " << w.wm[s] << " on path " << n;
      sum += w.wm[s];
    }
    ASSERT_TRUE(!w.hit || (w.wh >= 0 && w.wh <= 1)) << "path " << n;
    ASSERT_TRUE(!w.nee || (w.wn >= 0 && w.wn <= 1)) << "path " << n;
    saturated += w.clamped, rescaled += w.rescaled;
    if (w.hit || w.nee || sum > 0) {
      EXPECT_NEAR(sum, 1.0, 1e-3) << "path " << n << " (k = " << p.k << ", overflowed " << w.clamped << ")";
      ++checked;
    }
    if (HasFailure()) return;
  }
  std::printf(
      "paths rescaled beyond 2^+-400: %d, with a competitor beyond double: %d, of 50000; paths "
      "checked: %d\n",
      rescaled, saturated, checked);
  EXPECT_GT(rescaled, 1000);
  EXPECT_GT(checked, 40000);
}

// Without merge terms (no photon map) the hit and NEE weights are nimbus.pt's power heuristic.
TEST(CausticsMis, NoMapGivesPathTracerWeights) {
  std::mt19937_64 g(7);
  for (int n = 0; n < 10000; ++n) {
    const float bsdf = float(log_uniform(g, 1e-3, 1e3)), light = float(log_uniform(g, 1e-3, 1e3));
    CameraMis cm;
    const float wh = hit_weight(mis(light / bsdf), cm.s_cam(3), 1.0f, cm.clamped);
    const float wn = nee_weight(mis(bsdf / light), 1.0f, cm.s_cam(3), 1.0f, 1.0f, light, cm.clamped);
    const float ph = bsdf * bsdf / (bsdf * bsdf + light * light),
                pn = light * light / (bsdf * bsdf + light * light);
    EXPECT_NEAR(wh, ph, 1e-6f * std::max(ph, 1e-6f) + 1e-7f);
    EXPECT_NEAR(wn, pn, 1e-6f * std::max(pn, 1e-6f) + 1e-7f);
  }
}

// The pool's fireflies: camera -> water (delta) -> floor -> wall -> floor -> wall -> water (delta) -> sun.
// With lookups at the first two rough vertices only, both merge terms were dead (two adjacent rough
// vertices after them) and the BSDF hit of the sun (radiance ~4e4) had weight 1. With lookups at every
// rough vertex the merge at the last rough vertex exists and takes almost all the weight. Numbers from
// the pool at 640x360: r ~ 7 mm, ~1e5 photon paths per pass, sun lp = P_sel P_pos P_dir ~ 866.
TEST(CausticsMis, SunThroughWaterAfterSeveralDiffuseBouncesHasAMergeTechnique) {
  const float eta = 3.14159265f * 0.007f * 0.007f * 1e5f, lp = 866.0f;
  const float diffuse_pdf = 0.25f, cos_ = 0.8f;
  CameraMis cm;
  float r = 0;  // radius bookkeeping as the plugin does
  const bool rough[] = {false, true, true, true, true, false};
  uint32_t lookups = 0;
  for (uint32_t j = 1; j <= 6; ++j) {
    if (j >= 2) cm.arrive(cos_);
    const bool lookup = cm.append(rough[j - 1]);
    lookups += lookup;
    if (lookup && cm.rough_count == 1) r = 1.0f;
    const bool delta = !rough[j - 1];
    cm.scatter(cos_, delta ? 1.0f : diffuse_pdf, delta ? 1.0f : diffuse_pdf, lookup, j, eta * r * r);
  }
  EXPECT_EQ(lookups, 4u);
  // The sun is reached after 7 segments: the merge at x_5 (last rough vertex) is eligible.
  EXPECT_TRUE(cm.eligible(7));
  const float w = hit_weight(0.0f, cm.s_cam(7), lp, cm.clamped);
  EXPECT_LT(w, 1e-6f);
}

// A path whose vertex next to the light is rough (light -> floor -> glass -> floor -> camera) has no merge
// technique: the photon tracer ends such paths at that first vertex, so the camera side gives them to
// path tracing (NEE from the first floor vertex samples them), and nimbus.pt's weights apply.
TEST(CausticsMis, RoughFirstPhotonVertexHasNoMergeTechnique) {
  CameraMis cm;
  const bool rough[] = {true, false, true};  // x_1 floor (lookup), x_2 glass, x_3 floor
  for (uint32_t j = 1; j <= 3; ++j) {
    if (j >= 2) cm.arrive(0.8f);
    const bool lookup = cm.append(rough[j - 1]);
    if (j == 1) {
      EXPECT_FALSE(cm.eligible(2));  // no sharp vertex after x_1
    } else if (j == 2) {
      EXPECT_TRUE(cm.eligible(3));  // light -> glass -> floor: a caustic photon path
    }
    cm.scatter(0.8f, rough[j - 1] ? 0.25f : 1.0f, rough[j - 1] ? 0.25f : 1.0f, lookup, j, 100.0f);
  }
  // NEE from x_3 (rough, next to the light): no merge; the same path with x_3 sharp would have one.
  EXPECT_FALSE(cm.eligible(4));
  EXPECT_EQ(cm.s_cam(4).sum, 0.0);
  CameraMis sharp_end;
  const bool rough2[] = {true, false, false};
  for (uint32_t j = 1; j <= 3; ++j) {
    if (j >= 2) sharp_end.arrive(0.8f);
    const bool lookup = sharp_end.append(rough2[j - 1]);
    sharp_end.scatter(0.8f, rough2[j - 1] ? 0.25f : 1.0f, rough2[j - 1] ? 0.25f : 1.0f, lookup, j, 100.0f);
  }
  EXPECT_TRUE(sharp_end.eligible(4));
  EXPECT_GT(sharp_end.s_cam(4).sum, 0.0);
}

}  // namespace
}  // namespace nimbus::caustics
