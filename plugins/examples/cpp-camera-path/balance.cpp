// org.example.balance: a path tracer with the balance heuristic instead of nimbus.pt's power heuristic.
// Shows the camera-path layer: the pixel loop, film write, render elements, LightMix, next-event
// estimation and Russian roulette come from the SDK; the integrator supplies only what differs, here the
// two MIS weights of its path extension.
#include <nimbus/nimbus.hpp>

#include <nimbus/cpp/camera_path.hpp>

namespace example {

const char *const kRequired[] = {NIMBUS_CAMERA_PATH_SERVICES, nullptr};
const char *const kFeatures[] = {"progressive", "lightmix", nullptr};

float balance(float a, float b) { return a + b > 0 ? a / (a + b) : 0.0f; }

// The path extension: PlainPath's hooks, with balance-heuristic weights for BSDF hits and NEE.
struct BalancePath : nimbus::sdk::PlainPath {
  nimbus::sdk::PathWeight hit(const nimbus::sdk::LightHit &h) const {
    return {h.specular ? 1.0f : balance(h.bsdf_pdf, h.light_pdf)};
  }
  nimbus::sdk::PathWeight nee(const nimbus::sdk::LightSample &s) const {
    return {s.delta ? 1.0f : balance(s.light_pdf, s.bsdf_pdf)};
  }
};

class Balance final : public nimbus::sdk::CameraPathIntegrator<Balance> {
 public:
  NIMBUS_DESCRIPTOR("org.example.balance", "Example: path tracer, balance heuristic (C++)", "Example Inc.",
                    NIMBUS_KIND_INTEGRATOR, 1, 0, 0, kFeatures, kRequired)

  void sample(const nimbus_thread_ctx_t &ctx, uint32_t x, uint32_t y, nimbus_rng_t &rng,
              nimbus::sdk::SampleRecord &rec) const {
    BalancePath path;
    trace(ctx, x, y, rng, rec, path);
  }
};

}  // namespace example

NIMBUS_PLUGIN_LIBRARY(example::Balance)
