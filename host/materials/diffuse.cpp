#include "materials/diffuse.hpp"

#include <nimbus/cpp/sampling.hpp>

namespace nimbus {

Rgb DiffuseBsdf::eval(const Vec3f &wo, const Vec3f &wi, TransportMode, float *pdf_fwd, float *pdf_rev) const {
  const bool same = same_hemisphere(wo, wi);
  if (pdf_fwd) *pdf_fwd = same ? cosine_hemisphere_pdf(abs_cos_theta(wi)) : 0;
  if (pdf_rev) *pdf_rev = same ? cosine_hemisphere_pdf(abs_cos_theta(wo)) : 0;
  return same ? albedo_ * kInvPi : Rgb(0);
}

BsdfSample DiffuseBsdf::sample(const Vec3f &wo, float, Vec2f u, TransportMode) const {
  // At exactly grazing wo, eval() is zero for every wi: a sample would contradict it.
  if (wo.z == 0) return {};
  Vec3f wi = sample_cosine_hemisphere(u.x, u.y);
  if (wo.z < 0) wi.z = -wi.z;
  BsdfSample s;
  s.wi = wi;
  s.f = albedo_ * kInvPi;
  s.pdf = cosine_hemisphere_pdf(abs_cos_theta(wi));
  s.pdf_rev = cosine_hemisphere_pdf(abs_cos_theta(wo));
  s.lobe = NIMBUS_LOBE_REFLECTION | NIMBUS_LOBE_DIFFUSE;
  return checked_sample(s);
}

float DiffuseBsdf::pdf(const Vec3f &wo, const Vec3f &wi, TransportMode) const {
  return same_hemisphere(wo, wi) ? cosine_hemisphere_pdf(abs_cos_theta(wi)) : 0;
}

}  // namespace nimbus
