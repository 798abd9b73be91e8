// Light selection for photon emission (solver spec 6.1). Two groups: I (sun and environments) and F (the
// finite lights), half of the photon paths each when both emit. Within I a light weighs its photon
// power, within F its photon power over the squared distance from the camera to its bounds (at least
// eps^2, eps = max(its radius, 1e-3 R_scene)): lights near the camera light what it sees. The prior P0 is
// then adapted by what the photons did: over all previous maps, n_l uniform paths were emitted from
// light l and c_l of them had a photon that a lookup used with a non-zero contribution;
// s_l = (c_l + s) / (n_l + 1) with s = sum c / sum n (a sparsely sampled light shrinks towards the mean),
// and P_l = 0.8 P0_l s_l / sum_m P0_m s_m + 0.2 P0_l. The 20 % defensive share keeps every light
// reachable, which the guide's uniform samples and the MIS densities need. Only uniform paths count
// (chain paths are biased towards contributing ones). With LightMix, half of the paths pick a group
// uniformly (spec 6.1, "LightMix"), so that every group's layer converges on its own.
// The probabilities change only at photon passes: a map and the camera passes that read it see one table.
#pragma once

#include <cstdint>
#include <map>
#include <vector>

namespace nimbus::caustics {

class EmissionSelection {
 public:
  struct Light {
    double weight = 0;      // photon power (0: emits no photons)
    bool infinite = false;  // group I
    double distance2 = 1;   // finite: max(squared distance camera-bounds, eps^2)
    uint32_t group = 0;     // LightMix group
  };

  // adaptive false: photon power alone, never adapted (kept to measure the rule against).
  void configure(std::vector<Light> lights, bool lightmix, bool adaptive = true) {
    lights_ = std::move(lights), lightmix_ = lightmix, adaptive_ = adaptive;
    n_.assign(lights_.size(), 0), c_.assign(lights_.size(), 0);
  }
  // [main-thread] A uniform photon path of `light` from a finished map, and whether it contributed.
  void count(uint32_t light, bool contributed) {
    if (light >= n_.size()) return;
    ++n_[light];
    if (contributed) ++c_[light];
  }

  // The selection probability of each light (sums to 1 over the emitting lights, or all 0).
  std::vector<double> probabilities() const {
    const size_t n = lights_.size();
    std::vector<double> p0 = prior(), p(n, 0.0);
    double n_sum = 0, c_sum = 0;
    for (size_t l = 0; l < n; ++l) n_sum += double(n_[l]), c_sum += double(c_[l]);
    double adapted = 0;
    if (c_sum > 0 && adaptive_) {
      const double mean = c_sum / n_sum;
      for (size_t l = 0; l < n; ++l) adapted += p0[l] * (double(c_[l]) + mean) / (double(n_[l]) + 1);
    }
    for (size_t l = 0; l < n; ++l) {
      const double s = adapted > 0 ? (double(c_[l]) + c_sum / n_sum) / (double(n_[l]) + 1) : 0.0;
      p[l] = adapted > 0 ? kAdapted * p0[l] * s / adapted + (1 - kAdapted) * p0[l] : p0[l];
    }
    return lightmix_ ? balance_groups(p) : p;
  }

  template <class Writer>
  void save(Writer &w) const {
    w.put(uint64_t(n_.size()));
    for (size_t l = 0; l < n_.size(); ++l) w.put(n_[l]), w.put(c_[l]);
  }
  template <class Reader>
  bool restore(Reader &r) {
    uint64_t size = 0;
    if (!r.get(size) || size != n_.size()) return false;
    std::vector<uint64_t> n(size), c(size);
    for (size_t l = 0; l < size; ++l)
      if (!(r.get(n[l]) && r.get(c[l])) || c[l] > n[l]) return false;
    n_ = std::move(n), c_ = std::move(c);
    return true;
  }

 private:
  static constexpr double kAdapted = 0.8;  // the rest is the defensive share

  std::vector<double> prior() const {
    double sum[2] = {0, 0};  // F, I
    std::vector<double> pi(lights_.size(), 0.0);
    for (size_t l = 0; l < lights_.size(); ++l) {
      const Light &L = lights_[l];
      if (!(L.weight > 0)) continue;
      pi[l] = L.infinite || !adaptive_ ? L.weight : L.weight / L.distance2;
      sum[L.infinite] += pi[l];
    }
    if (!adaptive_) {
      for (double &w : pi) w /= sum[0] + sum[1];
      return pi;
    }
    const bool both = sum[0] > 0 && sum[1] > 0;
    for (size_t l = 0; l < lights_.size(); ++l)
      if (pi[l] > 0) pi[l] = (both ? 0.5 : 1.0) * pi[l] / sum[lights_[l].infinite];
    return pi;
  }
  std::vector<double> balance_groups(const std::vector<double> &p) const {
    std::map<uint32_t, double> group;
    for (size_t l = 0; l < p.size(); ++l)
      if (p[l] > 0) group[lights_[l].group] += p[l];
    std::vector<double> out(p.size(), 0.0);
    for (size_t l = 0; l < p.size(); ++l)
      if (p[l] > 0) out[l] = 0.5 * p[l] + 0.5 * p[l] / (group[lights_[l].group] * double(group.size()));
    return out;
  }

  std::vector<Light> lights_;
  bool lightmix_ = false, adaptive_ = true;
  std::vector<uint64_t> n_, c_;  // uniform paths emitted, and those that contributed, per light
};

}  // namespace nimbus::caustics
