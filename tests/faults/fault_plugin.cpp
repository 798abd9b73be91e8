// org.nimbus.test.faults: an integrator that misbehaves on command, for the host's fault tests. It renders
// an image whose every pixel is known exactly (beauty: a gradient, the element fault_splat: 1 from splats),
// so that a written image holding part of an iteration shows in its pixels. Its options pick the fault:
//   fault:           none | status | throw | nan | inf | outside_tile | sleep | missing_service
//   fault_hook:      prepare | begin_render | begin_iteration | render_tile | end_iteration
//   fault_iteration: the iteration of the per-iteration hooks that fails (tile 0 only, for render_tile)
//   fault_status:    the status returned by `status`; fault_seconds: how long `sleep` sleeps
#include <nimbus/nimbus.hpp>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <thread>

namespace faults {

const char *const kRequired[] = {"nimbus.host.film@1", nullptr};
const char *const kFaults[] = {"none",         "status", "throw",           "nan",  "inf",
                               "outside_tile", "sleep",  "missing_service", nullptr};
const char *const kHooks[] = {"prepare",     "begin_render",  "begin_iteration",
                              "render_tile", "end_iteration", nullptr};
const nimbus_option_decl_t kOptions[] = {
    {"fault", NIMBUS_OPTION_CHOICE, 0, "none", kFaults, "the fault to inject"},
    {"fault_hook", NIMBUS_OPTION_CHOICE, 0, "render_tile", kHooks, "the hook that fails"},
    {"fault_iteration", NIMBUS_OPTION_INT, 0, "3", nullptr, "the iteration it fails in"},
    {"fault_status", NIMBUS_OPTION_INT, 0, "-6", nullptr, "the status a `status` fault returns"},
    {"fault_seconds", NIMBUS_OPTION_FLOAT, 0, "600", nullptr, "how long a `sleep` fault sleeps"},
};

class FaultyIntegrator final : public nimbus::sdk::Integrator {
 public:
  NIMBUS_DESCRIPTOR_WITH_OPTIONS("org.nimbus.test.faults", "Test: fault injection", "Nimbus",
                                 NIMBUS_KIND_INTEGRATOR, 1, 0, 0, nullptr, kRequired, kOptions)

  nimbus_status_t init() override {
    film_ = host().service<nimbus_host_film_v1_t>(NIMBUS_SERVICE_FILM);
    return film_ ? NIMBUS_OK : NIMBUS_E_UNSUPPORTED;
  }

  nimbus_status_t prepare(const nimbus_render_setup_t &setup) override {
    width_ = setup.width, height_ = setup.height;
    for (uint32_t i = 0; i < setup.option_count; ++i) {
      const std::string key = setup.options[i].key, value = setup.options[i].value;
      if (key == "fault") fault_ = value;
      if (key == "fault_hook") hook_ = value;
      if (key == "fault_iteration") iteration_ = std::strtoull(value.c_str(), nullptr, 10);
      if (key == "fault_status") status_ = nimbus_status_t(std::atoi(value.c_str()));
      if (key == "fault_seconds") seconds_ = std::atof(value.c_str());
    }
    splat_ = film_->register_element(host().get(), "fault_splat", 3, NIMBUS_ELEMENT_SPLAT);
    return inject("prepare", 0);
  }
  nimbus_status_t begin_render(const nimbus_render_info_t &) override { return inject("begin_render", 0); }
  nimbus_status_t begin_iteration(uint64_t i) override { return inject("begin_iteration", i); }
  nimbus_status_t end_iteration(uint64_t i) override { return inject("end_iteration", i); }

  nimbus_status_t render_tile(const nimbus_thread_ctx_t &ctx, const nimbus_tile_t &tile) override {
    const bool first_tile = tile.x0 == 0 && tile.y0 == 0;
    const bool now = hook_ == "render_tile" && tile.iteration == iteration_;
    const nimbus_host_t *h = host().get();
    const float one[3] = {1, 1, 1};
    for (uint32_t y = tile.y0; y < tile.y1; ++y)
      for (uint32_t x = tile.x0; x < tile.x1; ++x) {
        float rgb[3] = {(float(x) + 0.5f) / float(width_), (float(y) + 0.5f) / float(height_), 0.25f};
        if (now && x == tile.x0 && y == tile.y0) {
          if (fault_ == "nan") rgb[1] = std::numeric_limits<float>::quiet_NaN();
          if (fault_ == "inf") rgb[0] = std::numeric_limits<float>::infinity();
        }
        film_->accumulate(h, &ctx, NIMBUS_ELEMENT_BEAUTY, x, y, rgb);
        film_->splat(h, &ctx, splat_, float(x) + 0.5f, float(y) + 0.5f, one);
        // A tile that ends in the middle of the failing pixel row: part of the iteration is written.
        if (now && first_tile && y == tile.y0 + 1 && x == tile.x0 + 3) {
          if (fault_ == "status") return status_;
          if (fault_ == "throw") throw std::runtime_error("injected fault in render_tile");
          if (fault_ == "sleep") std::this_thread::sleep_for(std::chrono::duration<double>(seconds_));
          if (fault_ == "missing_service") return missing_service();
        }
      }
    if (now && fault_ == "outside_tile" && tile.x1 < width_) {
      const float rgb[3] = {100, 100, 100};
      film_->accumulate(h, &ctx, NIMBUS_ELEMENT_BEAUTY, tile.x1, tile.y0, rgb);
    }
    return NIMBUS_OK;
  }

 private:
  // The fault of `hook`, when it is this one's turn (prepare and begin_render: at once).
  nimbus_status_t inject(const char *hook, uint64_t iteration) {
    if (hook_ != hook || (iteration != 0 && iteration != iteration_)) return NIMBUS_OK;
    if (fault_ == "status") return status_;
    if (fault_ == "throw") throw std::runtime_error(std::string("injected fault in ") + hook);
    if (fault_ == "sleep") std::this_thread::sleep_for(std::chrono::duration<double>(seconds_));
    if (fault_ == "missing_service") return missing_service();
    return NIMBUS_OK;
  }
  // Asks for a revision of the film service no host has, as a plugin built for a newer host might.
  nimbus_status_t missing_service() {
    if (host().service<void>(NIMBUS_SERVICE_FILM, 99)) return NIMBUS_OK;
    log(NIMBUS_LOG_ERROR, "needs nimbus.host.film revision 99");
    return NIMBUS_E_UNSUPPORTED;
  }

  const nimbus_host_film_v1_t *film_ = nullptr;
  nimbus_element_t splat_ = NIMBUS_ELEMENT_INVALID;
  uint32_t width_ = 1, height_ = 1;
  std::string fault_ = "none", hook_ = "render_tile";
  uint64_t iteration_ = 3;
  nimbus_status_t status_ = NIMBUS_E_INTERNAL;
  double seconds_ = 600;
};

}  // namespace faults

NIMBUS_PLUGIN_LIBRARY(faults::FaultyIntegrator)
