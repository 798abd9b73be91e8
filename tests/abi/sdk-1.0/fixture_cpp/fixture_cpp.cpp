// The C++ 1.0 fixture library (sdk-idioms.md §4.1): a trivial integrator through the 1.0 wrapper
// (nimbus.hpp as shipped) and a guide that does nothing harmful. The 1.0 wrapper has no Guide base
// class, so the guide fills the C guiding table itself on top of sdk::Plugin, as a 1.0 author had to.
#include <nimbus/nimbus.hpp>

#include <cstring>

namespace abi_fixture {
namespace {

const char *const kIntegratorNeeds[] = {"nimbus.host.film@1", nullptr};

// Writes one constant colour into every pixel: any difference in the output is the host's doing.
class ConstantIntegrator final : public nimbus::sdk::Integrator {
 public:
  NIMBUS_DESCRIPTOR("org.nimbus.abi.cpp.constant", "ABI 1.0 fixture: constant colour (C++ wrapper)",
                    "Nimbus tests", NIMBUS_KIND_INTEGRATOR, 1, 0, 0, nullptr, kIntegratorNeeds)

  nimbus_status_t init() override {
    film_ = host().service<nimbus_host_film_v1_t>(NIMBUS_SERVICE_FILM);
    return film_ ? NIMBUS_OK : NIMBUS_E_UNSUPPORTED;
  }

  nimbus_status_t render_tile(const nimbus_thread_ctx_t &ctx, const nimbus_tile_t &tile) override {
    static const float kColour[3] = {0.25f, 0.5f, 0.75f};
    for (uint32_t y = tile.y0; y < tile.y1; ++y)
      for (uint32_t x = tile.x0; x < tile.x1; ++x)
        film_->accumulate(host().get(), &ctx, NIMBUS_ELEMENT_BEAUTY, x, y, kColour);
    return NIMBUS_OK;
  }

 private:
  const nimbus_host_film_v1_t *film_ = nullptr;
};

// Asks for no photon paths and proposes the centre of the primary-sample space: harmless if bound.
class NullGuide final : public nimbus::sdk::Plugin {
 public:
  NIMBUS_DESCRIPTOR("org.nimbus.abi.cpp.guide", "ABI 1.0 fixture: null guide (C++ wrapper)", "Nimbus tests",
                    NIMBUS_KIND_GUIDING, 1, 0, 0, nullptr, nullptr)

  const void *interface(const char *id, uint32_t rev) override {
    return rev == 1 && std::strcmp(id, NIMBUS_IFACE_GUIDING) == 0 ? &table() : nullptr;
  }

 private:
  static const nimbus_guiding_v1_t &table() {
    static const nimbus_guiding_v1_t t = {
        sizeof(nimbus_guiding_v1_t),
        [](const nimbus_plugin_t *, const nimbus_scene_info_t *info) -> nimbus_status_t {
          return info ? NIMBUS_OK : NIMBUS_E_INVALID_ARG;
        },
        [](const nimbus_plugin_t *, uint64_t) -> nimbus_status_t { return NIMBUS_OK; },
        [](const nimbus_plugin_t *) -> uint64_t { return 0; },
        [](const nimbus_plugin_t *, const nimbus_thread_ctx_t *, uint64_t, float *u, uint32_t dims) {
          for (uint32_t i = 0; u && i < dims; ++i) u[i] = 0.5f;
        },
        [](const nimbus_plugin_t *, const nimbus_thread_ctx_t *, uint64_t, int32_t) {},
        [](const nimbus_plugin_t *, uint64_t, const nimbus_guide_stats_t *) {}};
    return t;
  }
};

}  // namespace
}  // namespace abi_fixture

NIMBUS_PLUGIN_LIBRARY(abi_fixture::ConstantIntegrator, abi_fixture::NullGuide)
