#include "materials/dielectric.hpp"

#include <optional>

namespace nimbus {

namespace {

// The microfacet normal that scatters wo into wi, by reflection or refraction.
struct HalfVector {
  Vec3f wm;        // upper hemisphere
  float etap;      // relative IOR seen from wo: 1 for reflection
  float etap_rev;  // relative IOR seen from wi
  float cos_m;     // reflection: wo . wm, equal to wi . wm, as |wo + wi| / 2 (the same from either side)
  bool reflection;
};

// pbrt-v4's generalised half vector wm ~ etap wi + wo, which covers reflection (etap = 1) and Walter's
// refraction half vector alike. Empty for grazing directions, a degenerate sum, or a microfacet that one
// of the two directions sees from behind (no single microfacet can connect them). Refraction sums the
// direction below the surface, scaled by eta, and the one above, whichever of the two is wo: the half
// vector of (wi, wo) is then bitwise that of (wo, wi), so a pdf and its reverse agree exactly.
std::optional<HalfVector> half_vector(const Vec3f &wo, const Vec3f &wi, float eta) {
  const float cos_o = cos_theta(wo), cos_i = cos_theta(wi);
  if (cos_o == 0 || cos_i == 0) return std::nullopt;
  const bool reflection = cos_o * cos_i > 0;
  const Vec3f h = reflection ? wi + wo : (cos_o > 0 ? wi * eta + wo : wo * eta + wi);
  const float len2 = length_squared(h);
  if (!(len2 > 0)) return std::nullopt;
  const Vec3f wm = face_forward(h / std::sqrt(len2), Vec3f(0, 0, 1));
  if (dot(wm, wi) * cos_i <= 0 || dot(wm, wo) * cos_o <= 0) return std::nullopt;
  if (reflection) return HalfVector{wm, 1, 1, std::copysign(0.5f * std::sqrt(len2), cos_o), true};
  return cos_o > 0 ? HalfVector{wm, eta, 1 / eta, 0, false} : HalfVector{wm, 1 / eta, eta, 0, false};
}

BsdfSample delta_sample(const Vec3f &wi, float f, uint32_t lobe, float etap) {
  BsdfSample s;
  s.wi = wi;
  s.f = Rgb(f);
  s.pdf = s.pdf_rev = 1;
  s.eta = etap;
  s.lobe = lobe | NIMBUS_LOBE_SPECULAR;
  return checked_sample(s);
}

// An index that is not a positive number makes the boundary index-matched rather than poisoning the film.
float valid_eta(float eta) { return std::isfinite(eta) && eta > 0 ? eta : 1.0f; }

}  // namespace

DielectricBsdf::DielectricBsdf(float eta, float alpha) : eta_(valid_eta(eta)), distrib_(alpha, alpha) {}

DielectricBsdf DielectricBsdf::dispersive(float eta_d, float alpha) {
  DielectricBsdf b(eta_d, alpha);
  b.dispersive_ = true;
  return b;
}

DielectricBsdf DielectricBsdf::with_eta(float eta) const {
  DielectricBsdf b = *this;
  b.eta_ = valid_eta(eta);
  b.dispersive_ = false;
  return b;
}

uint32_t DielectricBsdf::lobes() const {
  const uint32_t dispersion = dispersive_ ? NIMBUS_LOBE_DISPERSIVE : 0u;
  if (eta_ == 1) return NIMBUS_LOBE_TRANSMISSION | NIMBUS_LOBE_SPECULAR | dispersion;
  return NIMBUS_LOBE_REFLECTION | NIMBUS_LOBE_TRANSMISSION |
         (is_specular() ? NIMBUS_LOBE_SPECULAR : NIMBUS_LOBE_GLOSSY) | dispersion;
}

float DielectricBsdf::pdf_rough(const Vec3f &from, const Vec3f &to, const Vec3f &wm, float etap,
                                float fresnel, bool reflection) const {
  // Visible-normal density times the Jacobian d(wm)/d(to), times the probability of the lobe's choice.
  const float pdf_wm = distrib_.pdf(from, wm);
  if (reflection) return pdf_wm / (4 * abs_dot(from, wm)) * fresnel;
  const float denom = sqr(dot(to, wm) + dot(from, wm) / etap);
  return pdf_wm * abs_dot(to, wm) / denom * fresnel;
}

float DielectricBsdf::f_rough(const Vec3f &wo, const Vec3f &wi, const Vec3f &wm, float etap, float fresnel,
                              bool reflection, TransportMode mode) const {
  const float cos_o = cos_theta(wo), cos_i = cos_theta(wi);
  const float dg = distrib_.D(wm) * distrib_.G(wo, wi);
  if (reflection) return dg * fresnel / std::abs(4 * cos_i * cos_o);
  const float denom = sqr(dot(wi, wm) + dot(wo, wm) / etap) * cos_i * cos_o;
  const float f = dg * fresnel * std::abs(dot(wi, wm) * dot(wo, wm) / denom);
  return mode == TransportMode::Radiance ? f / sqr(etap) : f;
}

Rgb DielectricBsdf::eval(const Vec3f &wo, const Vec3f &wi, TransportMode mode, float *pdf_fwd,
                         float *pdf_rev) const {
  if (pdf_fwd) *pdf_fwd = 0;
  if (pdf_rev) *pdf_rev = 0;
  if (is_specular()) return Rgb(0);
  const std::optional<HalfVector> h = half_vector(wo, wi, eta_);
  if (!h) return Rgb(0);
  const Vec3f &wm = h->wm;
  // Transmittance from the side above the surface, so that eval(wi, wo) computes the same number.
  const Vec3f &above = cos_theta(wo) > 0 ? wo : wi, &below = cos_theta(wo) > 0 ? wi : wo;
  const float fresnel = h->reflection
                            ? fresnel_dielectric(h->cos_m, eta_)
                            : fresnel_dielectric_transmittance(abs_dot(above, wm), abs_dot(below, wm), eta_);
  const float f = f_rough(wo, wi, wm, h->etap, fresnel, h->reflection, mode);
  const float p_fwd = pdf_rough(wo, wi, wm, h->etap, fresnel, h->reflection);
  const float p_rev = pdf_rough(wi, wo, wm, h->etap_rev, fresnel, h->reflection);
  if (!std::isfinite(f) || !std::isfinite(p_fwd) || !std::isfinite(p_rev)) return Rgb(0);
  if (pdf_fwd) *pdf_fwd = p_fwd;
  if (pdf_rev) *pdf_rev = p_rev;
  return Rgb(f);
}

float DielectricBsdf::pdf(const Vec3f &wo, const Vec3f &wi, TransportMode mode) const {
  float p = 0;
  eval(wo, wi, mode, &p, nullptr);
  return p;
}

BsdfSample DielectricBsdf::sample(const Vec3f &wo, float uc, Vec2f u, TransportMode mode) const {
  if (wo.z == 0) return {};
  return is_specular() ? sample_specular(wo, uc, mode) : sample_rough(wo, uc, u, mode);
}

BsdfSample DielectricBsdf::sample_specular(const Vec3f &wo, float uc, TransportMode mode) const {
  if (eta_ == 1) return delta_sample(-wo, 1 / abs_cos_theta(wo), NIMBUS_LOBE_TRANSMISSION, 1);
  // Choosing the lobe with probability equal to its Fresnel weight makes every weight exactly 1.
  const float r = fresnel_dielectric(cos_theta(wo), eta_);
  if (uc < r) {
    const Vec3f wi(-wo.x, -wo.y, wo.z);
    return delta_sample(wi, 1 / abs_cos_theta(wi), NIMBUS_LOBE_REFLECTION, 1);
  }
  const std::optional<Refraction> t = refract(wo, Vec3f(0, 0, 1), eta_);
  if (!t) return {};
  float f = 1 / abs_cos_theta(t->wt);
  if (mode == TransportMode::Radiance) f /= sqr(t->etap);
  return delta_sample(t->wt, f, NIMBUS_LOBE_TRANSMISSION, t->etap);
}

BsdfSample DielectricBsdf::sample_rough(const Vec3f &wo, float uc, Vec2f u, TransportMode mode) const {
  const Vec3f wm = distrib_.sample_wm(wo, u);
  BsdfSample s;
  if (uc < fresnel_dielectric(dot(wo, wm), eta_)) {
    s.wi = reflect(wo, wm);
    if (!same_hemisphere(wo, s.wi)) return {};
    s.lobe = NIMBUS_LOBE_REFLECTION | NIMBUS_LOBE_GLOSSY;
  } else {
    const std::optional<Refraction> t = refract(wo, wm, eta_);
    if (!t || same_hemisphere(wo, t->wt) || t->wt.z == 0) return {};
    s.wi = t->wt;
    s.eta = t->etap;
    s.lobe = NIMBUS_LOBE_TRANSMISSION | NIMBUS_LOBE_GLOSSY;
  }
  // The weight and densities are eval()'s at the chosen direction, from the half vector it rebuilds:
  // near IOR 1 or at grazing angles the rebuild differs from wm by more than rounding, and a sample that
  // eval() would give zero density (its rebuilt microfacet flips side) must not be returned with a
  // density that every MIS weight and pdf() call elsewhere would contradict.
  s.f = eval(wo, s.wi, mode, &s.pdf, &s.pdf_rev);
  if (!(s.pdf > 0)) return {};
  return checked_sample(s);
}

}  // namespace nimbus
