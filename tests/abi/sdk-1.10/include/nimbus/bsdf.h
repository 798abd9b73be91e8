/* Nimbus SDK: the host's materials (nimbus.host.bsdf@1). Integrators evaluate, sample and query the
 * pdf of the BSDF at an interaction; they never reimplement one.
 *
 * Conventions: directions are world space, unit length, pointing away from the surface (wo towards the
 * previous vertex, wi towards the next). `f` is the BSDF value WITHOUT the cosine factor. pdfs are
 * solid-angle densities; for delta lobes pdf is 1 and f carries the delta's weight divided by |cos wi|
 * (so f * |cos| / pdf is the sample weight, as for any other lobe). */
#ifndef NIMBUS_BSDF_H
#define NIMBUS_BSDF_H

#include "scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Transport mode: radiance (camera paths) or importance (photons; adjoint shading-normal factor and
 * no 1/eta^2 radiance scaling at refractions). */
typedef uint32_t nimbus_transport_mode_t;
#define NIMBUS_MODE_RADIANCE 0u
#define NIMBUS_MODE_IMPORTANCE 1u

/* Lobe bits. lobes() may set bits beyond those a plugin knows (DISPERSIVE since 1.7): test bits with &,
 * never compare whole masks with ==. */
typedef uint32_t nimbus_lobe_t;
#define NIMBUS_LOBE_REFLECTION 1u
#define NIMBUS_LOBE_TRANSMISSION 2u
#define NIMBUS_LOBE_DIFFUSE 4u
#define NIMBUS_LOBE_GLOSSY 8u
#define NIMBUS_LOBE_SPECULAR 16u /* delta */
/* since 1.7: the material's index of refraction depends on the wavelength (see spectral.h) */
#define NIMBUS_LOBE_DISPERSIVE 32u

typedef struct nimbus_bsdf_sample {
  float wi[3];
  float f[3];         /* BSDF value, no cosine */
  float pdf;          /* solid-angle pdf of wi (1 for delta lobes) */
  float pdf_rev;      /* pdf of sampling wo given wi in the opposite mode (1 for delta lobes) */
  float eta;          /* relative IOR crossed (1 unless a refraction was sampled) */
  nimbus_lobe_t lobe; /* the single lobe sampled; 0 and pdf = 0 when sampling failed */
} nimbus_bsdf_sample_t;

#define NIMBUS_SERVICE_BSDF "nimbus.host.bsdf"
typedef struct nimbus_host_bsdf_v1 {
  uint32_t struct_size;
  /* [render-thread] f (out) and the forward/reverse pdfs pdf_fwd/pdf_rev (out, may be NULL) of wo -> wi.
   * Delta lobes contribute nothing here. ix, wo, wi borrowed. */
  void (*eval)(const nimbus_host_t *host, const nimbus_interaction_t *ix, const float wo[3],
               const float wi[3], nimbus_transport_mode_t mode, float f[3], float *pdf_fwd, float *pdf_rev);
  /* [render-thread] Samples wi given wo and three uniform numbers u. ix, wo, u borrowed; out is caller
   * storage, and out->pdf = 0 on failure. */
  void (*sample)(const nimbus_host_t *host, const nimbus_interaction_t *ix, const float wo[3],
                 const float u[3], nimbus_transport_mode_t mode, nimbus_bsdf_sample_t *out);
  /* [render-thread] Solid-angle pdf of sampling wi given wo (non-delta lobes only). ix, wo, wi borrowed. */
  float (*pdf)(const nimbus_host_t *host, const nimbus_interaction_t *ix, const float wo[3],
               const float wi[3], nimbus_transport_mode_t mode);
  /* [render-thread] Union of the lobes the material at ix (borrowed) has. */
  nimbus_lobe_t (*lobes)(const nimbus_host_t *host, const nimbus_interaction_t *ix);
  /* [render-thread] Minimum GGX alpha over the material's non-delta lobes (0 for delta-only materials,
   * 1 for diffuse): how sharp its sharpest lobe is. ix borrowed. */
  float (*min_roughness)(const nimbus_host_t *host, const nimbus_interaction_t *ix);
  /* [render-thread] Directional-hemispherical reflectance rgb (out) at ix seen from wo (ix, wo borrowed),
   * for the albedo element. */
  void (*albedo)(const nimbus_host_t *host, const nimbus_interaction_t *ix, const float wo[3], float rgb[3]);
} nimbus_host_bsdf_v1_t;

#ifdef __cplusplus
}
#endif

#endif /* NIMBUS_BSDF_H */
