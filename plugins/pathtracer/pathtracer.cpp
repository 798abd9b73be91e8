// nimbus.pt: unidirectional path tracing with next-event estimation, multiple importance sampling
// (power heuristic) between BSDF and light sampling, and Russian roulette. The baseline every other
// integrator is measured against (pbrt-v4's PathIntegrator is the model). The camera path is the SDK's
// camera-path layer with its plain estimator: this file only names the plugin.
#include <nimbus/nimbus.hpp>

#include <nimbus/cpp/camera_path.hpp>

namespace nimbus::pt {
namespace {

const char *const kRequired[] = {NIMBUS_CAMERA_PATH_SERVICES, nullptr};
// motion-blur: the camera-path layer gives every path a time when something moves (SDK 1.7);
// dispersion: a wavelength past a dispersive glass (SDK 1.7).
const char *const kFeatures[] = {"progressive", "lightmix", "motion-blur", "dispersion", nullptr};

class PathTracer final : public sdk::CameraPathIntegrator<PathTracer> {
 public:
  NIMBUS_DESCRIPTOR("nimbus.pt", "Path tracer (NEE + MIS)", "Nimbus", NIMBUS_KIND_INTEGRATOR, 1, 0, 0,
                    kFeatures, kRequired)

  void sample(const nimbus_thread_ctx_t &ctx, uint32_t x, uint32_t y, nimbus_rng_t &rng,
              sdk::SampleRecord &rec) const {
    sdk::PlainPath path;
    trace(ctx, x, y, rng, rec, path);
  }
};

}  // namespace
}  // namespace nimbus::pt

NIMBUS_PLUGIN_LIBRARY(nimbus::pt::PathTracer)
