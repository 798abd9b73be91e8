/* Nimbus SDK: wavelengths, for dispersion (nimbus.host.spectral@1, since 1.7). A scene may hold
 * dispersive dielectrics (glass whose index of refraction depends on the wavelength; lobes() reports
 * NIMBUS_LOBE_DISPERSIVE). Paths carry RGB as everywhere else until their first dispersive interaction;
 * from there on they carry one sampled wavelength lambda (nm, in [360, 830]) and scalar values, and
 * evaluate every material through this service. A scene without a dispersive material never needs it.
 *
 * Colours become spectra by Jakob & Hanika's (2019) smooth uplift: for any linear RGB colour c, the
 * integral of uplift(c)(lambda) * spectral_rgb_weight(lambda) over the visible range is c (up to the
 * uplift's fit error, below 1e-3 for colours the model reaches; greys are exact), so a path that samples
 * lambda with density p adds S(lambda) * spectral_rgb_weight(lambda) / p(lambda) to the RGB film
 * (<nimbus/cpp/spectral.hpp> has the weight and a wavelength sampler). */
#ifndef NIMBUS_SPECTRAL_H
#define NIMBUS_SPECTRAL_H

#include "bsdf.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Since 1.7. Every pointer parameter is borrowed for the call, except the outputs named below (caller
 * storage). A lambda outside [360, 830] nm (or NaN) is bad input: uplift returns 0, bsdf_sample fails
 * (pdf 0) and bsdf_eval returns f = 0 with pdfs 0. */
#define NIMBUS_SERVICE_SPECTRAL "nimbus.host.spectral"
typedef struct nimbus_host_spectral_v1 {
  uint32_t struct_size;
  /* [any-thread] 1 when the scene has a dispersive material: paths need wavelengths only then. */
  uint32_t (*dispersive)(const nimbus_host_t *host);
  /* [any-thread] The value at lambda (nm) of the smooth spectrum of linear rgb (any magnitude >= 0;
   * negative channels count as 0; homogeneous: uplift(k rgb) = k uplift(rgb)); rgb borrowed. A BSDF
   * value albedo / pi thus gives uplift(albedo) / pi. */
  float (*uplift)(const nimbus_host_t *host, const float rgb[3], float lambda);
  /* [render-thread] As nimbus_host_bsdf_v1_t.sample at one wavelength: dispersive dielectrics with
   * their index at lambda, every colour uplifted at lambda. ix, wo, u borrowed; out is caller storage,
   * and out->f holds the value in all three channels (out->pdf = 0 on failure). */
  void (*bsdf_sample)(const nimbus_host_t *host, const nimbus_interaction_t *ix, const float wo[3],
                      const float u[3], nimbus_transport_mode_t mode, float lambda,
                      nimbus_bsdf_sample_t *out);
  /* [render-thread] As nimbus_host_bsdf_v1_t.eval at one wavelength, as bsdf_sample. ix, wo, wi
   * borrowed; f is caller storage (the value in all three channels); pdf_fwd, pdf_rev are caller storage
   * or NULL. */
  void (*bsdf_eval)(const nimbus_host_t *host, const nimbus_interaction_t *ix, const float wo[3],
                    const float wi[3], nimbus_transport_mode_t mode, float lambda, float f[3], float *pdf_fwd,
                    float *pdf_rev);
} nimbus_host_spectral_v1_t;

#ifdef __cplusplus
}
#endif

#endif /* NIMBUS_SPECTRAL_H */
