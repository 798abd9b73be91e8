// Metal: a smooth or GGX-rough conductor with complex-IOR Fresnel, or an ideal mirror whose reflectance
// is the same at every angle. Reflects on both sides, like DiffuseBsdf.
#pragma once

#include <cstdint>

#include <nimbus/cpp/math.hpp>
#include "materials/scattering.hpp"

namespace nimbus {

class ConductorBsdf {
 public:
  // Complex IOR eta + i k per channel, relative to the outside medium. alpha < 1e-4 gives a delta lobe.
  static ConductorBsdf fresnel(const Rgb &eta, const Rgb &k, float alpha);
  // Reflects `reflectance` regardless of angle (no Fresnel).
  static ConductorBsdf mirror(const Rgb &reflectance, float alpha);

  Rgb eval(const Vec3f &wo, const Vec3f &wi, TransportMode mode, float *pdf_fwd, float *pdf_rev) const;
  BsdfSample sample(const Vec3f &wo, float uc, Vec2f u, TransportMode mode) const;
  float pdf(const Vec3f &wo, const Vec3f &wi, TransportMode mode) const;
  uint32_t lobes() const {
    return NIMBUS_LOBE_REFLECTION | (is_specular() ? NIMBUS_LOBE_SPECULAR : NIMBUS_LOBE_GLOSSY);
  }
  float min_alpha() const { return is_specular() ? 0.0f : std::min(distrib_.alpha_x(), distrib_.alpha_y()); }
  // The Fresnel reflectance at wo's angle: exact for the smooth case, and the rough lobe's reflectance
  // before masking losses, with no sampling and no noise.
  Rgb albedo(const Vec3f &wo) const { return fresnel_term(abs_cos_theta(wo)); }

  const TrowbridgeReitz &distribution() const { return distrib_; }

 private:
  ConductorBsdf(const Rgb &eta, const Rgb &k, const Rgb &reflectance, bool use_reflectance, float alpha)
      : eta_(eta),
        k_(k),
        reflectance_(reflectance),
        use_reflectance_(use_reflectance),
        distrib_(alpha, alpha) {}

  bool is_specular() const { return distrib_.effectively_smooth(); }
  Rgb fresnel_term(float cos_theta) const {
    return use_reflectance_ ? reflectance_ : fresnel_complex(cos_theta, eta_, k_);
  }
  // f and the pdf of reaching `to` from `from` through half vector wm, for a pair known to be valid.
  Rgb f_rough(const Vec3f &wo, const Vec3f &wi, const Vec3f &wm) const;
  float pdf_rough(const Vec3f &from, const Vec3f &wm) const;

  Rgb eta_, k_, reflectance_;
  bool use_reflectance_ = false;
  TrowbridgeReitz distrib_;
};

}  // namespace nimbus
