// nimbus.host.bsdf@1: world-space forwarding to the local-frame BSDFs, with the adjoint shading-normal
// correction for importance transport (Veach 1997, section 5.3).
#include "abi/host_services.hpp"
#include "abi/service_tables.hpp"

namespace nimbus {
namespace {

struct Local {
  const Bsdf *bsdf;
  Frame frame;
};

Local local_of(const nimbus_host_t *host, const nimbus_interaction_t *ix) {
  return {&context_of(host).bsdfs[ix->material],
          Frame::from_normal_tangent(Vec3f::load(ix->ns), Vec3f::load(ix->dpdu))};
}

TransportMode mode_of(nimbus_transport_mode_t m) {
  return m == NIMBUS_MODE_IMPORTANCE ? TransportMode::Importance : TransportMode::Radiance;
}

// Photons scatter with the adjoint BSDF: with shading normals it is not symmetric, so importance
// transport multiplies by |wo.ns||wi.ng| / (|wo.ng||wi.ns|) (wo: where the particle came from).
float adjoint_factor(const nimbus_interaction_t *ix, const Vec3f &wo, const Vec3f &wi) {
  const Vec3f ns = Vec3f::load(ix->ns), ng = Vec3f::load(ix->ng);
  const float den = std::abs(dot(wo, ng)) * std::abs(dot(wi, ns));
  return den > 0 ? std::abs(dot(wo, ns)) * std::abs(dot(wi, ng)) / den : 0.0f;
}

void eval(const nimbus_host_t *host, const nimbus_interaction_t *ix, const float wo[3], const float wi[3],
          nimbus_transport_mode_t mode, float f[3], float *pdf_fwd, float *pdf_rev) {
  const Local l = local_of(host, ix);
  const Vec3f wow = Vec3f::load(wo), wiw = Vec3f::load(wi);
  Rgb v = l.bsdf->eval(l.frame.to_local(wow), l.frame.to_local(wiw), mode_of(mode), pdf_fwd, pdf_rev);
  if (mode == NIMBUS_MODE_IMPORTANCE) v *= adjoint_factor(ix, wow, wiw);
  v.store(f);
}

void sample(const nimbus_host_t *host, const nimbus_interaction_t *ix, const float wo[3], const float u[3],
            nimbus_transport_mode_t mode, nimbus_bsdf_sample_t *out) {
  const Local l = local_of(host, ix);
  const Vec3f wow = Vec3f::load(wo);
  const BsdfSample s = l.bsdf->sample(l.frame.to_local(wow), u[0], {u[1], u[2]}, mode_of(mode));
  const Vec3f wiw = l.frame.to_world(s.wi);
  Rgb f = s.f;
  if (mode == NIMBUS_MODE_IMPORTANCE && s.pdf > 0) f *= adjoint_factor(ix, wow, wiw);
  const bool ok = s.pdf > 0 && std::isfinite(s.pdf) && is_finite(f);
  wiw.store(out->wi);
  (ok ? f : Rgb(0)).store(out->f);
  out->pdf = ok ? s.pdf : 0;
  out->pdf_rev = ok ? s.pdf_rev : 0;
  out->eta = s.eta;
  out->lobe = ok ? s.lobe : 0;
}

float pdf(const nimbus_host_t *host, const nimbus_interaction_t *ix, const float wo[3], const float wi[3],
          nimbus_transport_mode_t mode) {
  const Local l = local_of(host, ix);
  return l.bsdf->pdf(l.frame.to_local(Vec3f::load(wo)), l.frame.to_local(Vec3f::load(wi)), mode_of(mode));
}

nimbus_lobe_t lobes(const nimbus_host_t *host, const nimbus_interaction_t *ix) {
  return context_of(host).bsdfs[ix->material].lobes();
}

float min_roughness(const nimbus_host_t *host, const nimbus_interaction_t *ix) {
  return context_of(host).bsdfs[ix->material].min_alpha();
}

void albedo(const nimbus_host_t *host, const nimbus_interaction_t *ix, const float wo[3], float rgb[3]) {
  const Local l = local_of(host, ix);
  l.bsdf->albedo(l.frame.to_local(Vec3f::load(wo))).store(rgb);
}

}  // namespace

const nimbus_host_bsdf_v1_t kBsdfV1 = {sizeof(nimbus_host_bsdf_v1_t), eval, sample, pdf, lobes, min_roughness,
                                       albedo};

}  // namespace nimbus
