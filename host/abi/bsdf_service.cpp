// nimbus.host.bsdf@1: world-space forwarding to the local-frame BSDFs, with the adjoint shading-normal
// correction for importance transport (Veach 1997, section 5.3), and per-point BSDFs for textured
// materials (textures and normal maps).
#include "abi/local_bsdf.hpp"
#include "abi/service_tables.hpp"

namespace nimbus {
namespace {

using namespace abi_bsdf;

void eval(const nimbus_host_t *host, const nimbus_interaction_t *ix, const float wo[3], const float wi[3],
          nimbus_transport_mode_t mode, float f[3], float *pdf_fwd, float *pdf_rev) {
  const Vec3f wow = Vec3f::load(wo), wiw = Vec3f::load(wi);
  if (const DiffuseBsdf *d = plain_diffuse(host, ix)) {  // the commonest case, without a frame
    const Vec3f ns = Vec3f::load(ix->ns);
    Rgb v = d->eval(cosine_only(wow, ns), cosine_only(wiw, ns), mode_of(mode), pdf_fwd, pdf_rev);
    if (mode == NIMBUS_MODE_IMPORTANCE) v *= adjoint_factor(ix, ns, wow, wiw);
    v.store(f);
    return;
  }
  const Local l(host, ix);
  Rgb v = l.bsdf().eval(l.frame().to_local(wow), l.frame().to_local(wiw), mode_of(mode), pdf_fwd, pdf_rev);
  if (l.needs_factor(mode)) v *= l.factor(ix, mode, wow, wiw);
  v.store(f);
}

// The record of sample s, whose direction is wiw in world space and whose value f carries the factors of
// the transport mode and normal maps.
void write_sample(const BsdfSample &s, const Vec3f &wiw, const Rgb &f, nimbus_bsdf_sample_t *out) {
  const bool ok = s.pdf > 0 && std::isfinite(s.pdf) && is_finite(f);
  wiw.store(out->wi);
  (ok ? f : Rgb(0)).store(out->f);
  out->pdf = ok ? s.pdf : 0;
  out->pdf_rev = ok ? s.pdf_rev : 0;
  out->eta = s.eta;
  out->lobe = ok ? s.lobe : 0;
}

void sample(const nimbus_host_t *host, const nimbus_interaction_t *ix, const float wo[3], const float u[3],
            nimbus_transport_mode_t mode, nimbus_bsdf_sample_t *out) {
  const Vec3f wow = Vec3f::load(wo);
  if (const DiffuseBsdf *d = plain_diffuse(host, ix)) {  // the commonest case: no textures, no Local
    const Vec3f ns = Vec3f::load(ix->ns);
    const Frame frame = Frame::from_normal_tangent(ns, Vec3f::load(ix->dpdu));
    // A diffuse BSDF reads only wo's cosine (plain_diffuse).
    const BsdfSample s = d->sample(cosine_only(wow, ns), u[0], {u[1], u[2]}, mode_of(mode));
    const Vec3f wiw = frame.to_world(s.wi);
    Rgb f = s.f;
    if (mode == NIMBUS_MODE_IMPORTANCE && s.pdf > 0) f *= adjoint_factor(ix, ns, wow, wiw);
    write_sample(s, wiw, f, out);
    return;
  }
  const Local l(host, ix);
  const DiffuseBsdf *d = l.bsdf().diffuse();  // textured: a normal map may have moved the frame's normal
  const BsdfSample s = d ? d->sample(cosine_only(wow, l.frame().n), u[0], {u[1], u[2]}, mode_of(mode))
                         : l.bsdf().sample(l.frame().to_local(wow), u[0], {u[1], u[2]}, mode_of(mode));
  const Vec3f wiw = l.frame().to_world(s.wi);
  Rgb f = s.f;
  if (l.needs_factor(mode) && s.pdf > 0) f *= l.factor(ix, mode, wow, wiw);
  write_sample(s, wiw, f, out);
}

float pdf(const nimbus_host_t *host, const nimbus_interaction_t *ix, const float wo[3], const float wi[3],
          nimbus_transport_mode_t mode) {
  if (const DiffuseBsdf *d = plain_diffuse(host, ix)) {
    const Vec3f ns = Vec3f::load(ix->ns);
    return d->pdf(cosine_only(Vec3f::load(wo), ns), cosine_only(Vec3f::load(wi), ns), mode_of(mode));
  }
  const Local l(host, ix);
  return l.bsdf().pdf(l.frame().to_local(Vec3f::load(wo)), l.frame().to_local(Vec3f::load(wi)),
                      mode_of(mode));
}

nimbus_lobe_t lobes(const nimbus_host_t *host, const nimbus_interaction_t *ix) {
  return at_point(host, ix, [](const Bsdf &b) { return nimbus_lobe_t(b.lobes()); });
}

float min_roughness(const nimbus_host_t *host, const nimbus_interaction_t *ix) {
  return at_point(host, ix, [](const Bsdf &b) { return b.min_alpha(); });
}

void albedo(const nimbus_host_t *host, const nimbus_interaction_t *ix, const float wo[3], float rgb[3]) {
  const Local l(host, ix);
  l.bsdf().albedo(l.frame().to_local(Vec3f::load(wo))).store(rgb);
}

}  // namespace

const nimbus_host_bsdf_v1_t kBsdfV1 = {
    sizeof(nimbus_host_bsdf_v1_t), eval, sample, pdf, lobes, min_roughness, albedo};

}  // namespace nimbus
