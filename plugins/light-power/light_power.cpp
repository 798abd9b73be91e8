// nimbus.lights.power: picks lights in proportion to their emitted power (alias table), the same
// distribution for next-event estimation and photon emission. Lights with zero power are never picked.
#include <nimbus/nimbus.hpp>

#include <cmath>
#include <vector>

#include <nimbus/cpp/alias_table.hpp>

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

  nimbus_status_t prepare(const nimbus_scene_info_t &) override {
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

  uint32_t pick(const nimbus_interaction_t &, float u, float *pmf) override { return pick_emitter(u, pmf); }
  float pmf(const nimbus_interaction_t &, uint32_t light) override { return table_.pmf(light); }
  uint32_t pick_emitter(float u, float *pmf) override {
    const int64_t i = table_.sample(u, pmf);
    return i < 0 ? NIMBUS_NONE : uint32_t(i);
  }

 private:
  const nimbus_host_lights_v1_t *lights_ = nullptr;
  AliasTable table_;
};

}  // namespace
}  // namespace nimbus::lights

NIMBUS_PLUGIN_LIBRARY(nimbus::lights::PowerLightSampler)
