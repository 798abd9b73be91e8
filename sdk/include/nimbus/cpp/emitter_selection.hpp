// Light selection for photon emission (caustics solver spec 6.1), for light samplers that implement
// update_emission (light_sampler.h, since 1.6). Two groups: I (sun and environments) and F (the finite
// lights), half of the photon paths each when both emit. Within I a light weighs its photon power,
// within F its photon power over the squared distance from the camera to its bounds (at least eps^2,
// eps = max(its radius, 1e-3 R_scene)): lights near the camera light what it sees. The prior P0 is then
// adapted by what the photons did: over all previous passes, n_l uniform paths were emitted from light l
// and c_l of them had a photon that a lookup used; s_l = (c_l + s) / (n_l + 1) with s = sum c / sum n
// (a sparsely sampled light shrinks towards the mean), and P_l = 0.8 P0_l s_l / sum_m P0_m s_m + 0.2 D_l.
// The 20 % defensive share D is the same prior with each finite light's whole emitted power in place of
// its photon power (an integrator's photon power may count only what leaves towards sharp objects): a
// bright lamp that sees the glass small still makes caustics that matter where its light dominates. It
// keeps every light with photon power reachable, which a guide's uniform samples and the MIS densities
// need. With LightMix, half of the paths pick a group uniformly, so that every group's layer converges
// on its own. Before the first update, lights are picked by their emitted power.
#pragma once

#include <nimbus/light_sampler.h>
#include <nimbus/lights.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <vector>

#include <nimbus/cpp/alias_table.hpp>
#include <nimbus/cpp/math.hpp>

namespace nimbus::sdk {

class EmitterSelection {
 public:
  struct Light {
    double weight = 0;      // photon power (0: emits no photons)
    bool infinite = false;  // group I
    double distance2 = 1;   // finite: max(squared distance camera-bounds, eps^2)
    uint32_t group = 0;     // LightMix group
    double power = 0;       // finite: the whole emitted power, for the defensive share (0: weight)
  };

  // The rule: each light's probability (summing to 1 over the lights of positive weight, or all 0) from
  // the lights and, per light, the uniform paths emitted (n) and those that contributed (c); n and c
  // may be null (no pass yet).
  static std::vector<double> probabilities(const std::vector<Light> &lights, const uint64_t *n,
                                           const uint64_t *c, bool lightmix) {
    const size_t count = lights.size();
    std::vector<Light> whole = lights;
    for (Light &L : whole)
      if (L.weight > 0 && !L.infinite && L.power > 0) L.weight = L.power;
    const std::vector<double> p0 = prior(lights), d = prior(whole);
    std::vector<double> p(count, 0.0);
    double n_sum = 0, c_sum = 0;
    for (size_t l = 0; n && c && l < count; ++l) n_sum += double(n[l]), c_sum += double(std::min(c[l], n[l]));
    const double mean = c_sum > 0 ? c_sum / n_sum : 0.0;
    auto score = [&](size_t l) { return (double(std::min(c[l], n[l])) + mean) / (double(n[l]) + 1); };
    double adapted = 0;
    if (c_sum > 0)
      for (size_t l = 0; l < count; ++l) adapted += p0[l] * score(l);
    for (size_t l = 0; l < count; ++l)
      p[l] = (adapted > 0 ? kAdapted * p0[l] * score(l) / adapted : kAdapted * p0[l]) + (1 - kAdapted) * d[l];
    return lightmix ? balance_groups(lights, p) : p;
  }

  // [main-thread] The lights' kinds, bounds and groups from the host's lights service (borrowed) and the
  // scene's radius from info.
  nimbus_status_t prepare(const nimbus_host_t *host, const nimbus_host_lights_v1_t *lights,
                          const nimbus_scene_info_t &info) {
    const uint32_t n = lights->count(host);
    lights_.assign(n, {});
    std::vector<double> power(n, 0.0);
    for (uint32_t i = 0; i < n; ++i) {
      nimbus_light_info_t li{};
      li.header.struct_size = sizeof(li);
      if (lights->info(host, i, &li) != NIMBUS_OK) return NIMBUS_E_INTERNAL;
      const Vec3f lo = Vec3f::load(li.bounds_min), hi = Vec3f::load(li.bounds_max);
      power[i] = std::isfinite(li.power) && li.power > 0 ? li.power : 0.0;
      lights_[i] = {lo, hi, (li.flags & NIMBUS_LIGHT_INFINITE) != 0, li.group, power[i]};
    }
    scene_radius_ = info.scene_radius > 0 && std::isfinite(info.scene_radius) ? info.scene_radius : 1.0f;
    table_ = AliasTable(power);
    return NIMBUS_OK;
  }

  // [main-thread] Rebuilds the table from an integrator's feedback (light_sampler.h).
  nimbus_status_t update(const nimbus_emission_feedback_t &f) {
    if (f.light_count != lights_.size() || (f.light_count > 0 && !f.photon_power))
      return NIMBUS_E_INVALID_ARG;
    const Vec3f camera = Vec3f::load(f.camera);
    std::vector<Light> in(lights_.size());
    for (size_t l = 0; l < lights_.size(); ++l) {
      const Bounds &b = lights_[l];
      const Vec3f gap = max(max(b.lo - camera, camera - b.hi), Vec3f(0));
      const double eps = std::max(0.5 * double(length(b.hi - b.lo)), 1e-3 * double(scene_radius_));
      const double w = f.photon_power[l];
      in[l] = {std::isfinite(w) && w > 0 ? w : 0.0, b.infinite,
               std::max(double(length_squared(gap)), eps * eps), b.group, b.power};
    }
    table_ = AliasTable(probabilities(in, f.emitted, f.contributed, f.flags & NIMBUS_EMISSION_LIGHTMIX));
    return NIMBUS_OK;
  }

  // [render-thread] A light from u in [0,1) and its probability (out), or NIMBUS_NONE.
  uint32_t pick(float u, float *pmf) const {
    const int64_t i = table_.sample(u, pmf);
    return i < 0 ? NIMBUS_NONE : uint32_t(i);
  }
  // [render-thread] The probability that pick returns `light`.
  float pmf(uint32_t light) const { return table_.pmf(light); }

 private:
  static constexpr double kAdapted = 0.8;  // the rest is the defensive share

  struct Bounds {
    Vec3f lo, hi;
    bool infinite = false;
    uint32_t group = 0;
    double power = 0;  // emitted power (the host's)
  };

  static std::vector<double> prior(const std::vector<Light> &lights) {
    double sum[2] = {0, 0};  // F, I
    std::vector<double> pi(lights.size(), 0.0);
    for (size_t l = 0; l < lights.size(); ++l) {
      const Light &L = lights[l];
      if (!(L.weight > 0)) continue;
      pi[l] = L.infinite ? L.weight : L.weight / L.distance2;
      sum[L.infinite] += pi[l];
    }
    const bool both = sum[0] > 0 && sum[1] > 0;
    for (size_t l = 0; l < lights.size(); ++l)
      if (pi[l] > 0) pi[l] = (both ? 0.5 : 1.0) * pi[l] / sum[lights[l].infinite];
    return pi;
  }
  static std::vector<double> balance_groups(const std::vector<Light> &lights, const std::vector<double> &p) {
    std::map<uint32_t, double> group;
    for (size_t l = 0; l < p.size(); ++l)
      if (p[l] > 0) group[lights[l].group] += p[l];
    std::vector<double> out(p.size(), 0.0);
    for (size_t l = 0; l < p.size(); ++l)
      if (p[l] > 0) out[l] = 0.5 * p[l] + 0.5 * p[l] / (group[lights[l].group] * double(group.size()));
    return out;
  }

  std::vector<Bounds> lights_;
  float scene_radius_ = 1;
  AliasTable table_;
};

}  // namespace nimbus::sdk
