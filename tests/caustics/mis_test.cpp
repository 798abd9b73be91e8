// MIS partition of unity (solver spec 10 ii): synthetic paths with random vertex classes, pdfs, cosines
// and distances drive the production photon-side and camera-side state machines (mis.hpp) exactly as
// the plugin does; every weight they give must equal the closed form q_t^2 / sum_u q_u^2 built from
// explicit products of the area-measure pseudo-densities, and the weights must sum to one.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "light_paths.hpp"
#include "mis_synthetic_paths.hpp"

namespace nimbus::caustics {
namespace mis_test {

// ---- production state machines --------------------------------------------------------------------
struct PhotonAt {
  bool stored = false;
  float A = 0, B = 0;  // log2 A, log2 B (B with its vertices' effective counts folded in)
  bool b_valid = false, prev_rough = false;
};

struct Weights {
  double wh = 0, wn = 0, wt = 0;  // wt: the splat at x_1 (photon_splats.hpp)
  bool splatted = false;
  double wl = 0;  // the light path's connection at x_1 (light_paths.hpp)
  bool light_traced = false;
  std::vector<double> wm;
  bool hit = false, nee = false;
  std::vector<bool> merged;
  bool clamped = false;   // a weight's competitors overflowed double
  bool rescaled = false;  // a state left [2^-400, 2^400] (float would have overflowed long before)
};

// The light side of the light-tracing technique, as PhotonTracer::trace_light does: PhotonMis with lp_lt
// along the whole path, the photon tracer's rules for where photons would be stored, the weight at x_1.
void light_side(const SyntheticPath &p, Weights &w) {
  const uint32_t k = p.k;
  if (!(p.lt > 0) || !(p.lp_lt > 0) || !p.rough(1) || k < 3) return;  // direct light is path tracing's
  const float lp_lt = float(p.lp_lt);
  PhotonMis lm;
  lm.emit(p.hittable(), p.light == LightKind::Area ? float(p.cos_prev[k]) : 1.0f, lp_lt);
  bool had_sharp = false, prev_rough = false, alive = true;
  for (uint32_t j = k - 1; j >= 1; --j) {
    const float c_in = float(p.cos_next[j]);
    lm.arrive(c_in);
    const bool rough = p.rough(j);
    Mis E = 0;
    if (j == k - 1 && !p.delta(j))
      E = photon_nee_term(true, float(p.nk()), p.finite() ? float(p.d2[k - 1]) : 1.0f, lp_lt, c_in);
    const bool stored = alive && rough && had_sharp && (k - j) <= p.d_photon;
    if (j == 1) {
      const bool v1 = stored && p.lp > 0;
      const Mis neff = Mis(float(p.neff)), q = Mis(float(p.q_first)), area = Mis(float(p.area));
      const Mis rho = p.lp > 0 ? mis(Mis(float(p.lp)) / Mis(lp_lt)) : 0.0;
      w.wl = lt_weight(lm.log2_A(), lm.log2_B(), lm.b_valid, v1, float(p.w_cam[1]), mis(area * neff * q),
                       mis(neff * q), mis(neff * Mis(float(p.q_later))),
                       v1 && p.splat > 0 ? mis(Mis(p.splat)) : 0.0, rho, mis(Mis(p.lt)), w.clamped);
      w.light_traced = true;
      return;
    }
    if (rough && (j == k - 1 || prev_rough)) alive = false;
    lm.scatter(float(p.cos_prev[j]), float(p.w_light[j]), float(p.w_cam[j]), rough, stored, E);
    prev_rough = rough;
    had_sharp = had_sharp || !rough;
  }
}

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
  Weights w;
  w.rescaled = rescaled;
  light_side(p, w);
  // Camera side, as MergingPath does.
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
        const Mis lt =
            p.lp_lt > 0 && k >= 3 && cm.lt > 0 ? cm.lt_times(mis(Mis(float(p.lp_lt))), false) : 0.0;
        w.wh = hit_weight(nee_ratio, cm.s_cam(k), lp, cm.clamped, lt);
        w.hit = true;
      }
      break;
    }
    const bool lookup = cm.append(p.rough(j));
    // The plugin's radius: r_a, fixed at the first rough vertex.
    if (lookup && cm.rough_count == 1) area = Mis(float(p.area));
    // The plugin's factors in double (lookup_rank_factor): this vertex's, and the next rough one's for B.
    const Mis q = lookup_factor_at_rank(p, cm.rough_count);
    const Mis q_b = lookup_factor_at_rank(p, cm.rough_count + 1);
    // The production code's effective count at a lookup vertex: N_u (1 + c I) in double, as a float.
    const Mis neff_j = Mis(float(double(neff) * (1.0 + p.ratio * double(float(p.importance[j])))));
    // The splat technique's eta at x_1, as MergingPath and photon_splats.cpp compute it.
    const Mis eta_splat = j == 1 && lookup ? Mis(p.splat) : 0.0;
    if (j == 1 && lookup && p.lt > 0) cm.lt_first = mis(Mis(p.lt));
    const Mis rho = p.lp > 0 ? mis(Mis(float(p.lp_lt)) / Mis(float(p.lp))) : 0.0;  // a photon's, vs lp_lt
    if (lookup && at[j].stored && p.lp > 0) {
      const PhotonAt &ph = at[j];
      Mis lt = 0;
      if (rho > 0 && (j == 1 ? cm.lt_first > 0 : cm.lt > 0))
        lt = cm.lt_times(j == 1 ? rho : mis(Mis(float(p.w_light[j]))) * rho, j == 1);
      w.wm[j] = merge_weight(ph.A, ph.B, ph.b_valid, ph.prev_rough, float(p.w_cam[j]), float(p.w_light[j]),
                             mis(area * neff_j * q), mis(neff_j * q), mis(neff * q_b), cm.gamma_sum(k),
                             cm.clamped, mis(eta_splat), lt);
      w.merged[j] = true;
      if (eta_splat > 0) {
        w.wt = splat_weight(ph.A, ph.B, ph.b_valid, float(p.w_cam[j]), mis(area * neff_j * q),
                            mis(neff_j * q), mis(neff * q_b), mis(eta_splat), cm.clamped, cm.lt_first * rho);
        w.splatted = true;
      }
    }
    if (j == k - 1 && !p.delta(j)) {
      const float hit_ratio = p.hittable() ? mis(float(p.w_cam[j] / p.n_omega)) : 0.0f;
      Mis lt = 0;
      if (p.lp_lt > 0 && k >= 3 && cm.lt > 0) {
        const Mis ratio = mis(Mis(float(p.lp_lt)) * float(p.g_last()) / float(p.nk()));
        lt = cm.lt_times(mis(Mis(float(p.w_light[j]))) * ratio, false);
      }
      w.wn = nee_weight(hit_ratio, float(p.w_light[j]), cm.s_cam(k), lp, float(p.g_last()), float(p.nk()),
                        cm.clamped, lt);
      w.nee = true;
    }
    cm.scatter(float(p.cos_next[j]), float(p.w_cam[j]), float(p.w_light[j]), lookup, j, area * neff_j * q,
               eta_splat, j == 1 ? cm.lt_first : 0.0);
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
  int paths_with_merges = 0, long_chains = 0, splatted = 0, light_traced = 0;
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
    EXPECT_EQ(w.splatted, f.qt > 0) << "splat technique on path " << n;
    if (w.splatted) {
      expect_weight(w.wt, f.qt * f.qt / total, "splat", n);
      sum += w.wt;
      splatted += 1;
    }
    EXPECT_EQ(w.light_traced, f.ql > 0) << "light-tracing technique on path " << n;
    if (w.light_traced) {
      expect_weight(w.wl, f.ql * f.ql / total, "light path", n);
      sum += w.wl;
      light_traced += 1;
    }
    paths_with_merges += any_merge;
    long_chains += any_merge && p.k >= 8;
    EXPECT_NEAR(sum, 1.0, 1e-3) << "path " << n;
    if (HasFailure()) return;
  }
  std::printf("paths with merge techniques: %d (k >= 8: %d), with a splat technique: %d, light-traced: %d\n",
              paths_with_merges, long_chains, splatted, light_traced);
  EXPECT_GT(light_traced, 5000);
  EXPECT_GT(paths_with_merges, 10000);
  EXPECT_GT(splatted, 2000);
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
    double sum = (w.hit ? w.wh : 0.0) + (w.nee ? w.wn : 0.0) + (w.splatted ? w.wt : 0.0) +
                 (w.light_traced ? w.wl : 0.0);
    ASSERT_TRUE(!w.light_traced || (w.wl >= 0 && w.wl <= 1))
        << "light path weight " << w.wl << " on path " << n;
    ASSERT_TRUE(!w.splatted || (w.wt >= 0 && w.wt <= 1)) << "splat weight " << w.wt << " on path " << n;
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

}  // namespace mis_test
}  // namespace nimbus::caustics
