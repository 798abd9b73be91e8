// Photon paths (solver spec section 4): emission by the solver's light selection and projection maps,
// storage at rough vertices after a sharp one, termination after two consecutive rough vertices, and the
// photon-side MIS state of every stored photon.
#pragma once

#include <nimbus/nimbus.hpp>

#include <vector>

#include <nimbus/cpp/light_selection.hpp>
#include <nimbus/cpp/math.hpp>
#include <nimbus/cpp/path_services.hpp>
#include <nimbus/nimbus.hpp>

#include "emitters.hpp"
#include "mis.hpp"
#include "photon_map.hpp"
#include "schedule.hpp"

namespace nimbus::caustics {

// The output of one photon-pass task; a cache line of its own, since tasks on different workers update
// their chunks on every path.
struct alignas(sdk::kCacheLineBytes) PhotonChunk {
  std::vector<Photon> photons;
  uint64_t paths = 0;  // completed paths
  uint64_t work = 0;   // budget work units (schedule.hpp)
  // Empty for the next pass, keeping the buffers' memory.
  void reset() { photons.clear(), paths = 0, work = 0; }
};

// Random-number stream of photon path p of photon pass j: derive(p, j, kStreamPhoton).
inline constexpr uint64_t kStreamPhoton = 0x70686f746f6e;  // "photon"

// Traces photon paths against the scene, reading only state that is fixed during a photon pass.
class PhotonTracer {
 public:
  // selection: the camera paths' NEE light selection (the photon's first vertex weighs NEE from it).
  PhotonTracer(const nimbus_host_t *host, const sdk::PathServices &svc, const sdk::LightSelection &selection,
               const EmitterSet &emitters, uint32_t max_depth)
      : h_(host), svc_(svc), selection_(selection), emitters_(emitters), max_depth_(max_depth) {}

  // [render-thread] Photon path `path` of the `paths` of pass `pass` (1-based), into `out`.
  void trace(const nimbus_thread_ctx_t &ctx, uint64_t path, uint64_t paths, uint32_t pass,
             PhotonChunk &out) const;

 private:
  Rgb emitted(uint32_t light, const nimbus_light_emission_t &es, const Vec3f &w) const;
  Mis first_vertex_nee(const nimbus_interaction_t &ix, uint32_t light, const Emitter &em,
                       const nimbus_light_emission_t &es, const Vec3f &wo, float lp, float c_in) const;

  const nimbus_host_t *h_;
  const sdk::PathServices &svc_;
  const sdk::LightSelection &selection_;
  const EmitterSet &emitters_;
  uint32_t max_depth_;
};

}  // namespace nimbus::caustics
