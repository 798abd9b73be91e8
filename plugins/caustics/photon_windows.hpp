// Which photons a lookup merges by time (spec 7.1) and wavelength (spec 7.2).
//
// Time. Photons carry a scene time only when geometry or lights move while the
// shutter is open; a moving camera alone needs none, since photons live in world space.
//
// Times are compared in the shutter's own coordinate u = G(t), the share of the exposure before t: the
// number each path drew its time from, uniform for camera paths and photons alike whatever the shutter's
// curve, so photons carry no 1/g(t) factor. A lookup at u_c merges the photons with |u_p - u_c| < h, each
// with the factor 1/(2h), plus their mirror images in the shutter's ends (u_p -> -u_p, 2 - u_p). The
// mirrored kernel is symmetric and integrates to 1 over u_c for every u_p, so the film's average over the
// shutter is exact at any h; the spec's window shifted inside the shutter integrates to 1 over u_p only
// and leaves a bias at the shutter's ends that falls only as fast as h. h = (1/8) j^((alpha-1)/2) at pass
// j shrinks with the merge radius.
//
// Wavelength. A photon past a dispersive vertex carries its wavelength; a camera path past one merges
// such photons within h_lambda = 10 nm j^((alpha-1)/2) of its own (merging.cpp), mirrored at 360 and
// 830 nm. The spec's MIS factor 2 h_lambda p(lambda) for that case is left at 1: any factor shared by
// every technique's weight keeps the weights a partition of unity, so the image stays unbiased.
#pragma once

#include <nimbus/nimbus.hpp>

#include <algorithm>
#include <cmath>

#include <nimbus/cpp/spectral.hpp>

#include "schedule.hpp"

namespace nimbus::caustics {

// The photons one lookup accepts by a coordinate x in [lo, hi] (time as a share of the exposure, or
// wavelength): those within `half` of `center`, and their mirror images in lo and hi, each weighted by
// the kernel 1/(2 half). Mirrored, the kernel is symmetric and integrates to 1 over the centre for every
// photon, so averages over the whole range come out exact.
struct MirroredWindow {
  bool active = false;
  float lo = 0, hi = 1, center = 0, half = 0.5f;
  float kernel = 1;  // 1/(2 half)
  float rho = 1;     // the share of photons it accepts: the merge density's factor in MIS
  // The kernel's weight of a photon at x (0, 1 or 2 times `kernel`; 1 when inactive).
  float weight(float x) const {
    if (!active) return 1;
    const int n = int(std::abs(x - center) < half) + int((x - lo) + (center - lo) < half) +
                  int((hi - x) + (hi - center) < half);
    return float(n) * kernel;
  }
};
using TimeWindow = MirroredWindow;

// Whether photons need times, and the window of each pass.
class PhotonClock {
 public:
  // [main-thread] From the camera service's shutter (SDK 1.7): timed when geometry or lights move.
  // matched false: photons still carry times, but lookups merge photons of any time (for measurement).
  static PhotonClock of(const nimbus_host_t *h, const nimbus_host_camera_v1_t *camera, bool matched = true) {
    PhotonClock c;
    c.matched_ = matched;
    if (!NIMBUS_HAS_MEMBER(camera, nimbus_host_camera_v1_t, connect_at)) return c;
    float open = 0, close = 0;
    const uint32_t moving = camera->shutter(h, &open, &close);
    c.timed_ = (moving & (NIMBUS_MOTION_GEOMETRY | NIMBUS_MOTION_LIGHTS)) != 0 && close > open;
    return c;
  }
  bool timed() const { return timed_; }
  // Half the window's width at photon pass j (1-based), in shutter coordinates.
  static float half_width(uint32_t pass) {
    return 0.125f * std::pow(float(std::max(pass, 1u)), (kRadiusAlpha - 1) / 2);
  }
  // Half the wavelength window's width (nm) at photon pass j (1-based).
  static float lambda_half_width(uint32_t pass) {
    return 10.0f * std::pow(float(std::max(pass, 1u)), (kRadiusAlpha - 1) / 2);
  }
  // The wavelength window of a lookup by a camera path of wavelength lambda_c (0: RGB, no window);
  // h: lambda_half_width of the map's pass.
  static MirroredWindow lambda_window(float lambda_c, float h) {
    if (!(lambda_c > 0)) return {};
    return {true, kLambdaMin, kLambdaMax, lambda_c, h, 1 / (2 * h), 1};
  }
  // The window of a lookup by a camera path whose time came from u_c; h: half_width of the map's pass.
  TimeWindow window(float u_c, float h) const {
    if (!timed_ || !matched_) return {};
    return {true, 0, 1, u_c, h, 1 / (2 * h), 2 * h};
  }

 private:
  bool timed_ = false, matched_ = true;
};

}  // namespace nimbus::caustics
