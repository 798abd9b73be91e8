// The splat technique: light tracing on the solver's own photon paths. A stored photon that the camera
// sees directly is connected to the lens during its photon pass (one visibility ray), and every camera
// pass that uses the map adds it to the image with its MIS weight against the merge at the same vertex
// and everything that merge competes with (mis.hpp, splat_weight). Where the merge kernel covers many
// pixels, or the time window shuts out photons of other times (a moving caustic), the splat carries the
// caustic seen directly without the kernel's blur.
#pragma once

#include <nimbus/nimbus.hpp>

#include <atomic>
#include <cstdint>
#include <span>

#include <nimbus/cpp/math.hpp>
#include <nimbus/cpp/path_services.hpp>

#include "photon_map.hpp"

namespace nimbus::caustics {

struct MergeContext;
class PixelRadius;
class UsefulPixels;
class LightPathTrial;

// A stored photon's connection to the lens, made in its photon pass.
struct PhotonSplat {
  float raster[2];  // film position it lands at
  float value[3];   // photon power * f * |cos| * W at the lens: the pixel's light before 1 / N_u and MIS
  float w_cam;      // omega^C_1: pdf that a camera path at x_1 samples the photon's direction
  float density;    // C_1: the camera paths' density of first vertices there (mis.hpp, camera_density)
  float length;     // distance from the lens (the merge radius grows with it)
  uint32_t photon;  // its photon: index in its chunk, then in the pass
};

// What the photon tracer connects photons to the lens with; disabled, it makes no splats.
struct SplatCamera {
  bool enabled = false;
  Vec3f axis{0, 0, 1};  // the view axis (the ray through the film's centre)
  float theta_pix = 0;  // a pixel's angular width at the centre
};

// What one camera pass's splats read (fixed during the pass).
struct SplatInputs {
  const nimbus_host_t *host = nullptr;
  const nimbus_host_tasks_v1_t *tasks = nullptr;
  const nimbus_host_film_v1_t *film = nullptr;
  const nimbus_ext_lightmix_v1_t *lightmix = nullptr;  // null unless LightMix is active
  const MergeContext *merge = nullptr;
  const PixelRadius *pixel_radius = nullptr;
  UsefulPixels *useful = nullptr;  // takes each pixel's splatted light (the budget's per-pixel values)
  uint32_t width = 0, height = 0;
  std::span<const PhotonSplat> splats;
  std::span<const Photon> photons;
  LightPathTrial *trial = nullptr;  // takes it too while light paths are on trial (light_path_trial.hpp)
};

// [main-thread] Whether photons can be splatted: the camera connects points to the lens (SDK 1.1), the
// scene does not disperse light (a splat would carry one wavelength), and the pixel filter keeps a
// pixel's camera samples inside it, as a splat lands in the one pixel it hits.
inline bool splats_possible(const nimbus_host_t *h, const sdk::PathServices &svc,
                            const nimbus_host_spectral_v1_t *spectral) {
  if (spectral || !NIMBUS_HAS_MEMBER(svc.camera, nimbus_host_camera_v1_t, connect)) return false;
  for (const float u : {0.0f, 0.999f}) {
    const float uu[2] = {u, u};
    float film[2];
    svc.camera->sample_film(h, 0, 0, uu, film);
    if (!(film[0] >= 0 && film[0] < 1 && film[1] >= 0 && film[1] < 1)) return false;
  }
  return true;
}

// [main-thread] Splats every photon of `in` into beauty (and the `caustics` element and the photon's
// LightMix group when active) with its MIS weight for this camera pass; adds the weights whose
// competitors overflowed to `clamped`. Deterministic: the film sums splats per pixel in a fixed order.
nimbus_status_t splat_photons(const SplatInputs &in, uint64_t &clamped);

}  // namespace nimbus::caustics
