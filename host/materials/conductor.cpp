#include "materials/conductor.hpp"

namespace nimbus {

ConductorBsdf ConductorBsdf::fresnel(const Rgb &eta, const Rgb &k, float alpha) {
  // Negative components are meaningless; clamping keeps the Fresnel term in [0, 1].
  return {max(eta, Rgb(0)), max(k, Rgb(0)), Rgb(1), false, alpha};
}

ConductorBsdf ConductorBsdf::mirror(const Rgb &reflectance, float alpha) {
  return {Rgb(1), Rgb(0), max(reflectance, Rgb(0)), true, alpha};
}

Rgb ConductorBsdf::f_rough(const Vec3f &wo, const Vec3f &wi, const Vec3f &wm) const {
  const float cos_o = abs_cos_theta(wo), cos_i = abs_cos_theta(wi);
  return fresnel_term(abs_dot(wo, wm)) * (distrib_.D(wm) * distrib_.G(wo, wi) / (4 * cos_i * cos_o));
}

float ConductorBsdf::pdf_rough(const Vec3f &from, const Vec3f &wm) const {
  // Visible-normal density times the reflection Jacobian d(wm)/d(wi) = 1 / (4 |from . wm|).
  return distrib_.pdf(from, wm) / (4 * abs_dot(from, wm));
}

Rgb ConductorBsdf::eval(const Vec3f &wo, const Vec3f &wi, TransportMode, float *pdf_fwd,
                        float *pdf_rev) const {
  if (pdf_fwd) *pdf_fwd = 0;
  if (pdf_rev) *pdf_rev = 0;
  if (is_specular() || !same_hemisphere(wo, wi)) return Rgb(0);
  const Vec3f h = wo + wi;
  if (length_squared(h) == 0) return Rgb(0);
  // Same hemisphere, so wo . wm = wi . wm > 0 once wm faces wo's side.
  const Vec3f wm = face_forward(normalize(h), Vec3f(0, 0, 1));
  const Rgb f = f_rough(wo, wi, wm);
  if (!is_finite(f)) return Rgb(0);
  if (pdf_fwd) *pdf_fwd = pdf_rough(wo, wm);
  if (pdf_rev) *pdf_rev = pdf_rough(wi, wm);
  return f;
}

float ConductorBsdf::pdf(const Vec3f &wo, const Vec3f &wi, TransportMode mode) const {
  float p = 0;
  eval(wo, wi, mode, &p, nullptr);
  return p;
}

BsdfSample ConductorBsdf::sample(const Vec3f &wo, float, Vec2f u, TransportMode) const {
  if (wo.z == 0) return {};
  BsdfSample s;
  if (is_specular()) {
    s.wi = Vec3f(-wo.x, -wo.y, wo.z);
    s.f = fresnel_term(abs_cos_theta(wo)) / abs_cos_theta(s.wi);
    s.pdf = s.pdf_rev = 1;
    s.lobe = NIMBUS_LOBE_REFLECTION | NIMBUS_LOBE_SPECULAR;
    return checked_sample(s);
  }
  const Vec3f wm = distrib_.sample_wm(wo, u);
  const Vec3f wi = reflect(wo, wm);
  // Reflections off steep microfacets can leave through the surface: that mass is the masking loss.
  if (!same_hemisphere(wo, wi)) return {};
  s.wi = wi;
  s.f = f_rough(wo, wi, wm);
  s.pdf = pdf_rough(wo, wm);
  s.pdf_rev = pdf_rough(wi, wm);
  s.lobe = NIMBUS_LOBE_REFLECTION | NIMBUS_LOBE_GLOSSY;
  return checked_sample(s);
}

}  // namespace nimbus
