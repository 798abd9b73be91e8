// nimbus.host.bsdf@1: world-space forwarding to the local-frame BSDFs, with the adjoint shading-normal
// correction for importance transport (Veach 1997, section 5.3), and per-point BSDFs for textured
// materials (textures and normal maps).
#include <optional>

#include "abi/host_services.hpp"
#include "abi/service_tables.hpp"

namespace nimbus {
namespace {

TexturedMaterials::SurfacePoint surface_point(const nimbus_interaction_t *ix) {
  return {Vec3f::load(ix->ng), Vec3f::load(ix->ns), Vec3f::load(ix->dpdu), Vec3f::load(ix->dpdv),
          Vec2f{ix->uv[0], ix->uv[1]}};
}

// The BSDF and shading frame at an interaction. Untextured materials use the BSDF built with the scene (no
// lookups, no copies); textured ones get theirs built here from texture lookups at ix->uv, and a normal map
// replaces the shading normal.
class Local {
 public:
  Local(const nimbus_host_t *host, const nimbus_interaction_t *ix) : ns_(Vec3f::load(ix->ns)) {
    const World &world = world_of(host);
    const TexturedMaterials *textured = world.textures.get();
    if (!textured || !textured->textured(ix->material)) {
      bsdf_ = &world.bsdfs[ix->material];
    } else {
      const TexturedMaterials::Shading &s = own_.emplace(textured->shade(ix->material, surface_point(ix)));
      bsdf_ = &s.bsdf;
      ns_ = s.ns;
      mapped_ = s.normal_mapped;
    }
    frame_ = Frame::from_normal_tangent(ns_, Vec3f::load(ix->dpdu));
  }
  Local(const Local &) = delete;  // bsdf_ may point into the object

  const Bsdf &bsdf() const { return *bsdf_; }
  const Frame &frame() const { return frame_; }

  // What f is multiplied by on its way out, for a pair (wo, wi) in world space.
  // Importance transport: the adjoint BSDF with shading normals is not symmetric, so it carries
  // |wo.ns||wi.ng| / (|wo.ng||wi.ns|) (Veach 1997, section 5.3; wo: where the particle came from).
  // Normal maps: integrators multiply f by |wi.ns| with the interaction's ns, while the BSDF shades with
  // the mapped normal n'; f carries |wi.n'| / |wi.ns| so that the product is f |wi.n'|.
  float factor(const nimbus_interaction_t *ix, nimbus_transport_mode_t mode, const Vec3f &wo,
               const Vec3f &wi) const {
    float k = 1;
    if (mode == NIMBUS_MODE_IMPORTANCE) {
      const Vec3f ng = Vec3f::load(ix->ng);
      const float den = std::abs(dot(wo, ng)) * std::abs(dot(wi, ns_));
      k = den > 0 ? std::abs(dot(wo, ns_)) * std::abs(dot(wi, ng)) / den : 0.0f;
    }
    if (mapped_) {
      const float den = std::abs(dot(wi, Vec3f::load(ix->ns)));
      k *= den > 0 ? std::abs(dot(wi, ns_)) / den : 0.0f;
    }
    return k;
  }
  bool needs_factor(nimbus_transport_mode_t mode) const { return mode == NIMBUS_MODE_IMPORTANCE || mapped_; }

 private:
  const Bsdf *bsdf_ = nullptr;
  std::optional<TexturedMaterials::Shading> own_;  // textured materials only
  Vec3f ns_;
  bool mapped_ = false;
  Frame frame_;
};

// The BSDF for questions that do not depend on direction (lobes, min roughness): only a roughness texture
// makes those vary over the surface.
template <class F>
auto at_point(const nimbus_host_t *host, const nimbus_interaction_t *ix, F &&query) {
  const World &world = world_of(host);
  const TexturedMaterials *textured = world.textures.get();
  if (textured && textured->varies_lobes(ix->material))
    return query(textured->shade(ix->material, surface_point(ix)).bsdf);
  return query(world.bsdfs[ix->material]);
}

TransportMode mode_of(nimbus_transport_mode_t m) {
  return m == NIMBUS_MODE_IMPORTANCE ? TransportMode::Importance : TransportMode::Radiance;
}

void eval(const nimbus_host_t *host, const nimbus_interaction_t *ix, const float wo[3], const float wi[3],
          nimbus_transport_mode_t mode, float f[3], float *pdf_fwd, float *pdf_rev) {
  const Local l(host, ix);
  const Vec3f wow = Vec3f::load(wo), wiw = Vec3f::load(wi);
  Rgb v = l.bsdf().eval(l.frame().to_local(wow), l.frame().to_local(wiw), mode_of(mode), pdf_fwd, pdf_rev);
  if (l.needs_factor(mode)) v *= l.factor(ix, mode, wow, wiw);
  v.store(f);
}

void sample(const nimbus_host_t *host, const nimbus_interaction_t *ix, const float wo[3], const float u[3],
            nimbus_transport_mode_t mode, nimbus_bsdf_sample_t *out) {
  const Local l(host, ix);
  const Vec3f wow = Vec3f::load(wo);
  const BsdfSample s = l.bsdf().sample(l.frame().to_local(wow), u[0], {u[1], u[2]}, mode_of(mode));
  const Vec3f wiw = l.frame().to_world(s.wi);
  Rgb f = s.f;
  if (l.needs_factor(mode) && s.pdf > 0) f *= l.factor(ix, mode, wow, wiw);
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
