// A dielectric boundary (glass, water): smooth (delta reflection and refraction, chosen by Fresnel) or
// GGX-rough (Walter et al. 2007 with pbrt-v4's generalised half vector). eta is the IOR inside (below the
// surface, z < 0) over the IOR outside; eta == 1 is index-matched and passes light straight through.
#pragma once

#include <cstdint>

#include <nimbus/cpp/math.hpp>
#include "materials/scattering.hpp"

namespace nimbus {

class DielectricBsdf {
 public:
  DielectricBsdf(float eta, float alpha);
  // A glass whose index depends on wavelength, with eta its index for RGB transport (n_d): the same
  // boundary, but lobes() adds NIMBUS_LOBE_DISPERSIVE so that paths know to carry a wavelength here.
  static DielectricBsdf dispersive(float eta_d, float alpha);
  // This boundary with the index eta instead: a dispersive glass at one wavelength (not dispersive itself).
  DielectricBsdf with_eta(float eta) const;

  Rgb eval(const Vec3f &wo, const Vec3f &wi, TransportMode mode, float *pdf_fwd, float *pdf_rev) const;
  BsdfSample sample(const Vec3f &wo, float uc, Vec2f u, TransportMode mode) const;
  float pdf(const Vec3f &wo, const Vec3f &wi, TransportMode mode) const;
  uint32_t lobes() const;
  float min_alpha() const { return is_specular() ? 0.0f : std::min(distrib_.alpha_x(), distrib_.alpha_y()); }
  // Reflectance plus transmittance of a lossless boundary: 1 (what a denoiser's albedo expects of glass).
  Rgb albedo(const Vec3f &) const { return Rgb(1); }

  float eta() const { return eta_; }
  const TrowbridgeReitz &distribution() const { return distrib_; }

 private:
  // An index-matched boundary does not scatter, however rough.
  bool is_specular() const { return eta_ == 1 || distrib_.effectively_smooth(); }
  BsdfSample sample_specular(const Vec3f &wo, float uc, TransportMode mode) const;
  BsdfSample sample_rough(const Vec3f &wo, float uc, Vec2f u, TransportMode mode) const;
  // pdf of choosing the lobe through microfacet wm and landing on `to`, starting from `from`. etap is
  // the relative IOR seen from `from`; fresnel is the lobe's Fresnel factor (R or T), which sampling uses
  // as the lobe's probability.
  float pdf_rough(const Vec3f &from, const Vec3f &to, const Vec3f &wm, float etap, float fresnel,
                  bool reflection) const;
  // The rough BSDF value for a valid (wo, wm, wi) triple, same arguments.
  float f_rough(const Vec3f &wo, const Vec3f &wi, const Vec3f &wm, float etap, float fresnel, bool reflection,
                TransportMode mode) const;

  float eta_ = 1;
  TrowbridgeReitz distrib_;
  bool dispersive_ = false;
};

}  // namespace nimbus
