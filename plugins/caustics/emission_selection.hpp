// Light selection for photon emission (solver spec 6.1) is the bound light sampler's
// (light_sampler.h update_emission, since 1.6; the SDK kit's emitter_selection.hpp holds the rule).
// Before every photon pass the solver reports each light's photon power, the camera, and per light the
// uniform paths emitted and those a lookup used over all earlier passes (chain paths are biased towards
// contributing ones and are not counted); it then freezes the sampler's pmf_emitter into its own table,
// which the photons and the camera side read until the next pass. The counts are the solver's, saved with
// its state, so a resumed render rebuilds the same tables. A sampler without update_emission (built
// against an older SDK) gets the same rule from the kit inside the solver; `photon_light_selection:
// power` (kept for measurement) picks by photon power alone.
#pragma once

#include <nimbus/light_sampler.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <nimbus/cpp/emitter_selection.hpp>
#include <nimbus/cpp/math.hpp>

namespace nimbus::caustics {

class EmissionSelection {
 public:
  struct Inputs {
    std::vector<double> photon_power;  // per light (emitters.hpp: what its photons carry)
    Vec3f camera;
    float scene_radius = 1;
    bool lightmix = false;
    bool power_only = false;  // the measurement option
  };

  // [main-thread] A new render: the bound sampler (borrowed for the render) and the host's lights.
  nimbus_status_t configure(const nimbus_plugin_t *sampler, const nimbus_light_sampler_v1_t *iface,
                            const nimbus_host_t *host, const nimbus_host_lights_v1_t *lights, Inputs in) {
    in_ = std::move(in);
    n_.assign(in_.photon_power.size(), 0), c_.assign(in_.photon_power.size(), 0);
    sampler_ = sampler, iface_ = nullptr;
    if (NIMBUS_HAS_MEMBER(iface, nimbus_light_sampler_v1_t, pmf_emitter) && iface->update_emission &&
        iface->pmf_emitter)
      iface_ = iface;
    if (iface_ || in_.power_only) return NIMBUS_OK;
    nimbus_scene_info_t info{};
    info.header = {sizeof(info), NIMBUS_S_TYPE_SCENE_INFO, nullptr};
    info.light_count = uint32_t(in_.photon_power.size()), info.scene_radius = in_.scene_radius;
    return own_.prepare(host, lights, info);
  }
  // Whether the bound sampler chooses the photons' lights (else the kit's rule inside the solver does).
  bool by_sampler() const { return iface_ != nullptr && !in_.power_only; }

  // [main-thread] A uniform photon path of `light` from a finished map, and whether it contributed.
  void count(uint32_t light, bool contributed) {
    if (light >= n_.size()) return;
    ++n_[light];
    if (contributed) ++c_[light];
  }

  // [main-thread] The selection probability of each light for the next photon map (out); a sampler's
  // failure or an invalid probability is an error, `error` (out) says which.
  nimbus_status_t probabilities(std::vector<double> &p, std::string &error) {
    if (in_.power_only) return p = in_.photon_power, NIMBUS_OK;
    nimbus_emission_feedback_t f{};
    f.header = {sizeof(f), NIMBUS_S_TYPE_EMISSION_FEEDBACK, nullptr};
    f.light_count = uint32_t(n_.size()), f.flags = in_.lightmix ? NIMBUS_EMISSION_LIGHTMIX : 0u;
    in_.camera.store(f.camera);
    f.photon_power = in_.photon_power.data(), f.emitted = n_.data(), f.contributed = c_.data();
    const nimbus_status_t s = iface_ ? iface_->update_emission(sampler_, &f) : own_.update(f);
    if (s != NIMBUS_OK) return error = "update_emission failed", s;
    p.assign(n_.size(), 0.0);
    for (uint32_t l = 0; l < n_.size(); ++l) {
      const float q = iface_ ? iface_->pmf_emitter(sampler_, l) : own_.pmf(l);
      if (!(q >= 0 && q <= 1))
        return error = "pmf_emitter of light " + std::to_string(l) + " is not in [0, 1]", NIMBUS_E_INTERNAL;
      p[l] = in_.photon_power[l] > 0 ? double(q) : 0.0;
    }
    return NIMBUS_OK;
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
  Inputs in_;
  const nimbus_plugin_t *sampler_ = nullptr;
  const nimbus_light_sampler_v1_t *iface_ = nullptr;  // null: the kit's rule in own_
  sdk::EmitterSelection own_;
  std::vector<uint64_t> n_, c_;  // uniform paths emitted, and those that contributed, per light
};

}  // namespace nimbus::caustics
