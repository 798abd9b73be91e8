// Guides of "nimbus.iface.guiding" rev 2 (nimbus/guiding.h, since 1.5) in C++: sdk::PhotonGuide, whose
// trampolines fill nimbus_guiding_v2_t as sdk::Guide (nimbus.hpp) fills rev 1's table, and
// sdk::GuideTracer, a typed view of the tracer an integrator lends a chain.
//
//   class MyGuide final : public nimbus::sdk::PhotonGuide {
//    public:
//     NIMBUS_DESCRIPTOR("org.example.guide", ..., NIMBUS_KIND_GUIDING, ...)
//     nimbus_status_t begin_pass(const nimbus_guide_pass_t &pass) override;
//     nimbus_status_t run_chain(const nimbus_thread_ctx_t &ctx, uint32_t chain, sdk::GuideTracer &tracer,
//                               nimbus_guide_totals_t &totals) override;
//   };
//   NIMBUS_PLUGIN_LIBRARY(MyGuide)
//
// Part of the C++20 kit (std::span) rather than of nimbus.hpp, which stays C++17.
#pragma once

#include <nimbus/guiding.h>
#include <nimbus/nimbus.hpp>

#include <cstdint>
#include <cstring>
#include <span>
#include <stdexcept>

namespace nimbus::sdk {

// One traced path: its target value T and the name the integrator gave it for credit.
struct TracedPath {
  double target = 0;
  uint64_t path = 0;
};

// The tracer an integrator lends one run_chain (borrowed for that call, used on its thread only).
class GuideTracer {
 public:
  explicit GuideTracer(const nimbus_guide_tracer_t &t) : t_(&t) {}

  uint32_t dims() const { return t_->dims; }
  // Traces u (dims() values in [0, 1)) as a path of `kind` (NIMBUS_GUIDE_UNIFORM or _PROPOSAL). A vector of
  // another length throws: the integrator would read dims() values from it.
  TracedPath trace(std::span<const float> u, uint32_t kind) {
    if (u.size() != t_->dims) throw std::invalid_argument("trace: u does not have the tracer's dims values");
    TracedPath r;
    r.target = t_->trace(t_->user, u.data(), kind, &r.path);
    return r;
  }
  // Credits `multiplicity` chain steps to `path`; credits to one path add up.
  void credit(uint64_t path, uint64_t multiplicity) { t_->credit(t_->user, path, multiplicity); }

 private:
  const nimbus_guide_tracer_t *t_;
};

// Base class for guides of rev 2. The trampolines refuse null or short structs with NIMBUS_E_INVALID_ARG
// before a hook sees them, and zero the counts of run_chain's totals first, so a chain that fails (or
// throws) reports no paths.
class PhotonGuide : public Plugin {
 public:
  // [main-thread, !rendering] A render starts: forget the previous render's passes.
  virtual nimbus_status_t prepare(const nimbus_scene_info_t &) { return NIMBUS_OK; }
  // [main-thread]
  virtual nimbus_status_t begin_pass(const nimbus_guide_pass_t &pass) = 0;
  // [render-thread] Runs chain `chain` through `tracer` and fills the counts of `totals`. Calls for
  // different chains run at once: only per-chain state may be written.
  virtual nimbus_status_t run_chain(const nimbus_thread_ctx_t &ctx, uint32_t chain, GuideTracer &tracer,
                                    nimbus_guide_totals_t &totals) = 0;
  // [main-thread] `totals` are the integrator's sums over the pass's chains.
  virtual nimbus_status_t end_pass(const nimbus_guide_totals_t &) { return NIMBUS_OK; }

  const void *interface(const char *id, uint32_t rev) override {
    return (rev == 2 && std::strcmp(id, NIMBUS_IFACE_GUIDING) == 0) ? &table() : nullptr;
  }

 private:
  static PhotonGuide *self(const nimbus_plugin_t *p) { return static_cast<PhotonGuide *>(from(p)); }
  static bool complete(const nimbus_guide_tracer_t *t) {
    return t && t->struct_size >= sizeof(nimbus_guide_tracer_t) && t->trace && t->credit;
  }
  static const nimbus_guiding_v2_t &table() {
    static const nimbus_guiding_v2_t t = {
        sizeof(nimbus_guiding_v2_t),
        [](const nimbus_plugin_t *p, const nimbus_scene_info_t *i) {
          if (!i) return NIMBUS_E_INVALID_ARG;
          return self(p)->guarded("prepare", [&] { return self(p)->prepare(*i); });
        },
        [](const nimbus_plugin_t *p, const nimbus_guide_pass_t *pass) {
          if (!pass || pass->header.struct_size < sizeof(nimbus_guide_pass_t)) return NIMBUS_E_INVALID_ARG;
          return self(p)->guarded("begin_pass", [&] { return self(p)->begin_pass(*pass); });
        },
        [](const nimbus_plugin_t *p, const nimbus_thread_ctx_t *ctx, uint32_t chain,
           const nimbus_guide_tracer_t *tracer, nimbus_guide_totals_t *totals) {
          if (!ctx || !complete(tracer) || !totals) return NIMBUS_E_INVALID_ARG;
          totals->uniform_paths = totals->chain_steps = totals->proposals = totals->accepted = 0;
          totals->uniform_target_sum = 0;
          return self(p)->guarded("run_chain", [&] {
            GuideTracer view(*tracer);
            return self(p)->run_chain(*ctx, chain, view, *totals);
          });
        },
        [](const nimbus_plugin_t *p, const nimbus_guide_totals_t *totals) {
          if (!totals) return NIMBUS_E_INVALID_ARG;
          return self(p)->guarded("end_pass", [&] { return self(p)->end_pass(*totals); });
        }};
    return t;
  }
};

}  // namespace nimbus::sdk
