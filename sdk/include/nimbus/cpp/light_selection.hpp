// Light selection for next-event estimation in the camera-path layer (and for an integrator's own
// densities of it): the bound light sampler's choice, or, while LightMix is requested, a defensive
// mixture: half the sampler's choice, half a LightMix group drawn uniformly (among groups with a light of
// positive power) and a light of it by power. Users rescale LightMix layers, so each layer must converge
// at a rate that does not depend on its group's power; without LightMix, beauty-optimal selection stays.
#pragma once

#include <nimbus/light_sampler.h>

#include <algorithm>
#include <cstdint>
#include <vector>

#include <nimbus/cpp/alias_table.hpp>

namespace nimbus::sdk {

class LightSelection {
 public:
  // [main-thread] The sampler (borrowed, bound for the render) and the lights' LightMix groups and powers.
  void prepare(const nimbus_plugin_t *sampler, const nimbus_light_sampler_v1_t *iface,
               const std::vector<uint32_t> &groups, const std::vector<float> &powers) {
    sampler_ = sampler, iface_ = iface, groups_ = groups, powers_ = powers;
    set_lightmix(false);
  }

  // [main-thread] Whether LightMix is requested for this render: builds the per-group tables.
  void set_lightmix(bool on) {
    mix_ = false;
    within_.clear(), members_.clear(), group_slot_.assign(groups_.size(), -1);
    if (!on) return;
    std::vector<std::vector<double>> weights;
    for (size_t l = 0; l < groups_.size(); ++l) {
      const double p = powers_[l] > 0 && powers_[l] < 3.4e38f ? double(powers_[l]) : 0.0;
      if (p <= 0) continue;
      size_t g = 0;
      while (g < members_.size() && groups_[members_[g].front()] != groups_[l]) ++g;
      if (g == members_.size()) members_.emplace_back(), weights.emplace_back();
      members_[g].push_back(uint32_t(l)), weights[g].push_back(p);
    }
    if (members_.empty()) return;
    for (size_t g = 0; g < members_.size(); ++g) {
      within_.emplace_back(weights[g]);
      for (size_t k = 0; k < members_[g].size(); ++k) group_slot_[members_[g][k]] = int64_t(g << 32 | k);
    }
    mix_ = true;
  }
  bool lightmix() const { return mix_; }

  // [render-thread] A light for NEE at ix (borrowed) from u_pick (and, with LightMix, u_mix), with the
  // probability of choosing it (out).
  uint32_t pick(const nimbus_interaction_t *ix, float u_pick, float u_mix, float *pmf) const {
    if (!mix_) return iface_->pick(sampler_, ix, u_pick, pmf);
    uint32_t light = 0;
    if (u_mix < 0.5f) {
      float p = 0;
      light = iface_->pick(sampler_, ix, u_pick, &p);
    } else {
      const size_t g = std::min(members_.size() - 1, size_t(u_pick * float(members_.size())));
      const float u = u_pick * float(members_.size()) - float(g);
      const int64_t k = within_[g].sample(u < 1 ? u : 0.99999994f);
      light = members_[g][size_t(k < 0 ? 0 : k)];
    }
    *pmf = this->pmf(ix, light);
    return light;
  }
  // [render-thread] The probability that pick() chooses `light` at ix (borrowed).
  float pmf(const nimbus_interaction_t *ix, uint32_t light) const {
    const float sampler = iface_->pmf(sampler_, ix, light);
    if (!mix_) return sampler;
    const int64_t slot = light < group_slot_.size() ? group_slot_[light] : -1;
    const float group =
        slot < 0 ? 0.0f : within_[size_t(slot >> 32)].pmf(size_t(slot & 0xffffffff)) / float(members_.size());
    return 0.5f * sampler + 0.5f * group;
  }

 private:
  const nimbus_plugin_t *sampler_ = nullptr;
  const nimbus_light_sampler_v1_t *iface_ = nullptr;
  std::vector<uint32_t> groups_;
  std::vector<float> powers_;
  bool mix_ = false;
  std::vector<std::vector<uint32_t>> members_;  // lights of positive power, per group
  std::vector<AliasTable> within_;              // their selection by power
  std::vector<int64_t> group_slot_;             // per light: group << 32 | index in it, or -1
};

}  // namespace nimbus::sdk
