// Lambertian reflection, lit from either side (a single-sided plane seen from behind still reflects).
#pragma once

#include <cstdint>

#include <nimbus/cpp/math.hpp>
#include <nimbus/cpp/sampling.hpp>
#include "materials/scattering.hpp"

namespace nimbus {

class DiffuseBsdf {
 public:
  // The default matches MaterialDesc's, so a default Bsdf equals make_bsdf(MaterialDesc{}).
  DiffuseBsdf() = default;
  explicit DiffuseBsdf(const Rgb &albedo) : albedo_(albedo) {}

  // Defined here, not in a .cpp: the BSDF services call them at every diffuse vertex, and inlined into
  // them they cost no call.
  Rgb eval(const Vec3f &wo, const Vec3f &wi, TransportMode, float *pdf_fwd, float *pdf_rev) const {
    const bool same = same_hemisphere(wo, wi);
    if (pdf_fwd) *pdf_fwd = same ? cosine_hemisphere_pdf(abs_cos_theta(wi)) : 0;
    if (pdf_rev) *pdf_rev = same ? cosine_hemisphere_pdf(abs_cos_theta(wo)) : 0;
    return same ? albedo_ * kInvPi : Rgb(0);
  }
  BsdfSample sample(const Vec3f &wo, float, Vec2f u, TransportMode) const {
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
  float pdf(const Vec3f &wo, const Vec3f &wi, TransportMode) const {
    return same_hemisphere(wo, wi) ? cosine_hemisphere_pdf(abs_cos_theta(wi)) : 0;
  }
  uint32_t lobes() const { return NIMBUS_LOBE_REFLECTION | NIMBUS_LOBE_DIFFUSE; }
  float min_alpha() const { return 1; }
  Rgb albedo(const Vec3f &) const { return albedo_; }

 private:
  Rgb albedo_{0.8f, 0.8f, 0.8f};
};

}  // namespace nimbus
