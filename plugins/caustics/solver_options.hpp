// The solver's descriptor lists and options: the one switch users see, and the choices kept for
// measurement (docs/performance.md compares against them), parsed from the render setup.
#pragma once

#include <nimbus/nimbus.hpp>

#include <cstdlib>
#include <cstring>

#include <nimbus/cpp/path_services.hpp>

namespace nimbus::caustics {

const char *const kRequired[] = {NIMBUS_CAMERA_PATH_SERVICES, "nimbus.host.tasks@1", nullptr};
// The host binds the Metropolis photon guide unless the scene names another or none (SDK 1.5). Motion
// blur and dispersion: camera paths take the layer's times and wavelengths, photons their own
// (photon_windows.hpp).
const char *const kFeatures[] = {"progressive", "photon-pass", "lightmix",
                                 "motion-blur", "dispersion",  "default-guide=nimbus.guide.metropolis",
                                 nullptr};
// The switch, and three choices kept for measurement (docs/performance.md compares against them).
const char *const kEmissionChoices[] = {"uniform", "adaptive-map", "guided", nullptr};
const char *const kSelectionChoices[] = {"adaptive", "power", nullptr};
// Uniform emission is the default: neither the emission map nor guided passes rendered lower error at
// equal time across the caustic scenes (docs/performance.md §8).
const char *const kTimeChoices[] = {"matched", "ignored", nullptr};  // what motion blur's lookups merge
const nimbus_option_decl_t kOptions[] = {
    {"caustics", NIMBUS_OPTION_SWITCH, 0, "on", nullptr,
     "caustics by photon merging; off renders exactly what nimbus.pt renders"},
    {"photon_emission", NIMBUS_OPTION_CHOICE, 0, "uniform", kEmissionChoices,
     "photon paths uniform, from an emission map learnt from the paths lookups used, or chosen by the "
     "bound guide's chains (Metropolis photon guiding)"},
    {"photon_light_selection", NIMBUS_OPTION_CHOICE, 0, "adaptive", kSelectionChoices,
     "for measurement: lights chosen for photons by camera distance and usefulness, or by power alone"},
    {"photon_times", NIMBUS_OPTION_CHOICE, 0, "matched", kTimeChoices,
     "for measurement: lookups merge photons of similar time only (motion blur), or of any time"},
    {"photon_memory_mb", NIMBUS_OPTION_INT, 0, "0", nullptr,
     "resource limit: MiB one photon pass may use (0: a quarter of the machine's memory); a pass that "
     "could need more traces fewer paths"}};

struct SolverOptions {
  bool enabled = true;  // the `caustics` switch
  bool uniform_emission = true, adaptive_map = false, power_selection = false;
  bool times_matched = true;
  uint64_t photon_memory_mb = 0;  // 0: a quarter of the machine's memory (photon_budget.hpp)

  // [main-thread] The host validated the values against kOptions; an absent option is its default.
  static SolverOptions of(const nimbus_render_setup_t &setup) {
    const auto is = [&](const char *key, const char *value) {
      const char *v = sdk::option_value(setup, key);
      return v && std::strcmp(v, value) == 0;
    };
    SolverOptions o;
    o.enabled = !is("caustics", "off");
    o.uniform_emission = !is("photon_emission", "guided");
    o.adaptive_map = is("photon_emission", "adaptive-map");
    o.power_selection = is("photon_light_selection", "power");
    o.times_matched = !is("photon_times", "ignored");
    if (const char *mb = sdk::option_value(setup, "photon_memory_mb"); mb && mb[0] != '-')
      o.photon_memory_mb = std::strtoull(mb, nullptr, 10);
    return o;
  }
};

}  // namespace nimbus::caustics
