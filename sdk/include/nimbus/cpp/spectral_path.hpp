// A path's colour state for dispersion (SDK 1.7, nimbus/spectral.h): RGB until the path's first
// dispersive vertex, then one wavelength. At that vertex the path draws lambda ~ p (the kit's visible
// wavelength density), and its throughput beta becomes
//   spectral_rgb_weight(lambda) * uplift(beta)(lambda) / p(lambda)
// (the spec's "throughput converted at lambda, divided by p"): from then on every BSDF value and every
// light's radiance is a scalar at lambda (the host's spectral service), multiplying all three channels,
// so the path's contributions stay RGB and need nothing else downstream. A scene without a dispersive
// material never leaves RGB: no number is drawn and no call changes. Requires C++17.
#pragma once

#include <nimbus/nimbus.hpp>

#include <nimbus/cpp/math.hpp>
#include <nimbus/cpp/spectral.hpp>

namespace nimbus::sdk {

class PathSpectrum {
 public:
  PathSpectrum() = default;
  // service: the host's spectral service when the scene is dispersive, else null (every path is RGB).
  PathSpectrum(const nimbus_host_t *h, const nimbus_host_spectral_v1_t *service,
               const nimbus_host_bsdf_v1_t *bsdf)
      : h_(h), spectral_(service), bsdf_(bsdf) {}

  // [main-thread] The host's spectral service if the scene needs wavelengths, else null.
  static const nimbus_host_spectral_v1_t *needed(const Host &host) {
    const auto *s = host.service<nimbus_host_spectral_v1_t>(NIMBUS_SERVICE_SPECTRAL);
    return s && NIMBUS_HAS_MEMBER(s, nimbus_host_spectral_v1_t, bsdf_eval) && s->dispersive(host.get())
               ? s
               : nullptr;
  }

  bool mono() const { return lambda_ > 0; }
  float lambda() const { return lambda_; }

  // At a vertex with `lobes`: a path still in RGB that meets a dispersive material takes a wavelength,
  // drawn with `next()` (called only then), and converts beta. weigh: fold the colour weight of lambda
  // into beta (camera paths); without it beta is the scalar value in all three channels (photons, whose
  // lookups weigh it by the camera path's wavelength or colour). Returns whether it did.
  template <class Next>
  bool disperse(nimbus_lobe_t lobes, Next &&next, Rgb &beta, bool weigh = true) {
    if (!spectral_ || mono() || !(lobes & NIMBUS_LOBE_DISPERSIVE)) return false;
    lambda_ = sample_visible_wavelength(next());
    const float pdf = visible_wavelength_pdf(lambda_);
    float rgb[3];
    beta.store(rgb);
    const float value = pdf > 0 ? spectral_->uplift(h_, rgb, lambda_) / pdf : 0.0f;
    beta = weigh ? spectral_rgb_weight(lambda_) * value : Rgb(value);
    return true;
  }

  // Radiance (or any colour) arriving along the path: itself in RGB, its value at lambda once mono.
  Rgb light(const Rgb &L) const {
    if (!mono()) return L;
    float rgb[3];
    L.store(rgb);
    return Rgb(spectral_->uplift(h_, rgb, lambda_));
  }

  // The host's BSDF, at lambda once mono (arguments as nimbus_host_bsdf_v1_t's).
  void sample(const nimbus_interaction_t *ix, const float wo[3], const float u[3],
              nimbus_transport_mode_t mode, nimbus_bsdf_sample_t *out) const {
    if (mono())
      spectral_->bsdf_sample(h_, ix, wo, u, mode, lambda_, out);
    else
      bsdf_->sample(h_, ix, wo, u, mode, out);
  }
  void eval(const nimbus_interaction_t *ix, const float wo[3], const float wi[3],
            nimbus_transport_mode_t mode, float f[3], float *pdf_fwd, float *pdf_rev) const {
    if (mono())
      spectral_->bsdf_eval(h_, ix, wo, wi, mode, lambda_, f, pdf_fwd, pdf_rev);
    else
      bsdf_->eval(h_, ix, wo, wi, mode, f, pdf_fwd, pdf_rev);
  }

 private:
  const nimbus_host_t *h_ = nullptr;
  const nimbus_host_spectral_v1_t *spectral_ = nullptr;
  const nimbus_host_bsdf_v1_t *bsdf_ = nullptr;
  float lambda_ = 0;  // 0: RGB
};

}  // namespace nimbus::sdk
