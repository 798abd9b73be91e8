// nimbus.lights.power: picks lights for next-event estimation in proportion to their emitted power (alias
// table); lights with zero power are never picked. Photon emission picks by power too until an
// integrator's feedback adapts it by the SDK kit's rule (emitter_selection.hpp).
#include <nimbus/nimbus.hpp>

#include <cmath>
#include <vector>

#include <nimbus/cpp/alias_table.hpp>
#include <nimbus/cpp/emitter_selection.hpp>

namespace nimbus::lights {
namespace {

const char *const kRequired[] = {"nimbus.host.lights@1", nullptr};

class PowerLightSampler final : public sdk::LightSampler {
 public:
  NIMBUS_DESCRIPTOR("nimbus.lights.power", "Power-proportional light sampler", "Nimbus",
                    NIMBUS_KIND_LIGHT_SAMPLER, 1, 0, 0, nullptr, kRequired)

  nimbus_status_t init() override {
    lights_ = host().service<nimbus_host_lights_v1_t>(NIMBUS_SERVICE_LIGHTS);
    return lights_ ? NIMBUS_OK : NIMBUS_E_UNSUPPORTED;
  }

  nimbus_status_t prepare(const nimbus_scene_info_t &scene) override {
    if (nimbus_status_t s = emission_.prepare(host().get(), lights_, scene); s != NIMBUS_OK) return s;
    const uint32_t n = lights_->count(host().get());
    std::vector<double> power(n, 0.0);
    for (uint32_t i = 0; i < n; ++i) {
      nimbus_light_info_t info{};
      info.header.struct_size = sizeof(info);
      if (lights_->info(host().get(), i, &info) != NIMBUS_OK) return NIMBUS_E_INTERNAL;
      power[i] = std::isfinite(info.power) && info.power > 0 ? info.power : 0.0;
    }
    table_ = AliasTable(power);
    return NIMBUS_OK;
  }

  uint32_t pick(const nimbus_interaction_t &, float u, float *pmf) override {
    const int64_t i = table_.sample(u, pmf);
    return i < 0 ? NIMBUS_NONE : uint32_t(i);
  }
  float pmf(const nimbus_interaction_t &, uint32_t light) override { return table_.pmf(light); }
  uint32_t pick_emitter(float u, float *pmf) override { return emission_.pick(u, pmf); }
  bool adapts_emission() const override { return true; }
  nimbus_status_t update_emission(const nimbus_emission_feedback_t &f) override {
    return emission_.update(f);
  }
  float pmf_emitter(uint32_t light) override { return emission_.pmf(light); }

 private:
  const nimbus_host_lights_v1_t *lights_ = nullptr;
  AliasTable table_;
  sdk::EmitterSelection emission_;  // photon emission
};

}  // namespace
}  // namespace nimbus::lights

NIMBUS_PLUGIN_LIBRARY(nimbus::lights::PowerLightSampler)
