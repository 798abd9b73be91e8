// Nimbus SDK C++ wrapper: the base class of rev-1 guides, kept so that their sources still compile
// (nimbus.hpp includes it).
#pragma once

#include "nimbus.hpp"

#include <algorithm>
#include <cstring>

namespace nimbus::sdk {

// Base class for guides of "nimbus.iface.guiding" rev 1 (SDK 1.1-1.4). Hosts still serve the table, but
// no render drives it: since 1.5 the host binds rev 2 guides (nimbus/cpp/photon_guide.hpp). Chains are
// per worker (ctx.worker_index), so no locks.
class Guide : public Plugin {
 public:
  virtual nimbus_status_t prepare(const nimbus_scene_info_t &) { return NIMBUS_OK; }
  virtual nimbus_status_t begin_iteration(uint64_t) { return NIMBUS_OK; }
  // Photon paths wanted in this iteration.
  virtual uint64_t budget() = 0;
  // Fill u[0, dims) with the primary-sample vector of photon path `path`.
  virtual void propose(const nimbus_thread_ctx_t &ctx, uint64_t path, float *u, uint32_t dims) = 0;
  virtual void report(const nimbus_thread_ctx_t &, uint64_t, bool) {}
  virtual void end_iteration(uint64_t, const nimbus_guide_stats_t &) {}

  const void *interface(const char *id, uint32_t rev) override {
    return (rev == 1 && std::strcmp(id, NIMBUS_IFACE_GUIDING) == 0) ? &table() : nullptr;
  }

 private:
  static Guide *self(const nimbus_plugin_t *p) { return static_cast<Guide *>(from(p)); }
  // Hooks without a status log an exception and go on: budget() falls back to 0 (no photon paths),
  // propose() leaves the zero vector it was handed, so a failing guide degrades to no guidance.
  template <class F>
  static void quiet(const nimbus_plugin_t *p, const char *hook, F &&f) noexcept {
    self(p)->guarded(hook, [&] {
      f();
      return NIMBUS_OK;
    });
  }
  static const nimbus_guiding_v1_t &table() {
    static const nimbus_guiding_v1_t t = {
        sizeof(nimbus_guiding_v1_t),
        [](const nimbus_plugin_t *p, const nimbus_scene_info_t *i) {
          return self(p)->guarded("prepare", [&] { return self(p)->prepare(*i); });
        },
        [](const nimbus_plugin_t *p, uint64_t it) {
          return self(p)->guarded("begin_iteration", [&] { return self(p)->begin_iteration(it); });
        },
        [](const nimbus_plugin_t *p) {
          uint64_t n = 0;
          quiet(p, "budget", [&] { n = self(p)->budget(); });
          return n;
        },
        [](const nimbus_plugin_t *p, const nimbus_thread_ctx_t *c, uint64_t path, float *u, uint32_t dims) {
          std::fill(u, u + dims, 0.0f);
          quiet(p, "propose", [&] { self(p)->propose(*c, path, u, dims); });
        },
        [](const nimbus_plugin_t *p, const nimbus_thread_ctx_t *c, uint64_t path, int32_t visible) {
          quiet(p, "report", [&] { self(p)->report(*c, path, visible != 0); });
        },
        [](const nimbus_plugin_t *p, uint64_t it, const nimbus_guide_stats_t *stats) {
          const nimbus_guide_stats_t none{sizeof(nimbus_guide_stats_t), 0, 0, 0};
          quiet(p, "end_iteration", [&] { self(p)->end_iteration(it, stats ? *stats : none); });
        }};
    return t;
  }
};

}  // namespace nimbus::sdk
