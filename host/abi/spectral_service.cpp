// nimbus.host.spectral@1: wavelengths for dispersion. The BSDF calls are the bsdf service's at one
// wavelength: the same point, frame and factors (textures, normal maps, importance transport), with the
// material's SpectralBsdf in place of its RGB one.
#include "abi/local_bsdf.hpp"
#include "abi/service_tables.hpp"
#include "core/rgb_uplift_table.hpp"
#include "materials/spectral_bsdf.hpp"

namespace nimbus {
namespace {

using namespace abi_bsdf;

uint32_t dispersive(const nimbus_host_t *host) { return world_of(host).dispersive() ? 1u : 0u; }

float uplift_rgb(const nimbus_host_t *, const float rgb[3], float lambda) {
  return uplift(Vec3f::load(rgb), lambda);
}

SpectralBsdf spectral(const nimbus_host_t *host, const nimbus_interaction_t *ix, const Local &l,
                      float lambda) {
  return SpectralBsdf(l.bsdf(), world_of(host).dispersion_of(ix->material), lambda);
}

void bsdf_sample(const nimbus_host_t *host, const nimbus_interaction_t *ix, const float wo[3],
                 const float u[3], nimbus_transport_mode_t mode, float lambda, nimbus_bsdf_sample_t *out) {
  const Local l(host, ix);
  const Vec3f wow = Vec3f::load(wo);
  const BsdfSample s =
      spectral(host, ix, l, lambda).sample(l.frame().to_local(wow), u[0], {u[1], u[2]}, mode_of(mode));
  const Vec3f wiw = l.frame().to_world(s.wi);
  float f = s.f.x;
  if (l.needs_factor(mode) && s.pdf > 0) f *= l.factor(ix, mode, wow, wiw);
  const bool ok = s.pdf > 0 && std::isfinite(s.pdf) && std::isfinite(f);
  wiw.store(out->wi);
  Rgb(ok ? f : 0.0f).store(out->f);
  out->pdf = ok ? s.pdf : 0;
  out->pdf_rev = ok ? s.pdf_rev : 0;
  out->eta = s.eta;
  out->lobe = ok ? s.lobe : 0;
}

void bsdf_eval(const nimbus_host_t *host, const nimbus_interaction_t *ix, const float wo[3],
               const float wi[3], nimbus_transport_mode_t mode, float lambda, float f[3], float *pdf_fwd,
               float *pdf_rev) {
  const Local l(host, ix);
  const Vec3f wow = Vec3f::load(wo), wiw = Vec3f::load(wi);
  float v = spectral(host, ix, l, lambda)
                .eval(l.frame().to_local(wow), l.frame().to_local(wiw), mode_of(mode), pdf_fwd, pdf_rev);
  if (l.needs_factor(mode)) v *= l.factor(ix, mode, wow, wiw);
  Rgb(v).store(f);
}

}  // namespace

const nimbus_host_spectral_v1_t kSpectralV1 = {sizeof(nimbus_host_spectral_v1_t), dispersive, uplift_rgb,
                                               bsdf_sample, bsdf_eval};

}  // namespace nimbus
