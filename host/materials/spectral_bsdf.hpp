// A material's BSDF at one wavelength, for paths that carry a wavelength since they met a dispersive
// material: a dispersive dielectric refracts with its index at lambda; every other material scatters as
// it does in RGB, its value uplifted to a smooth spectrum (Jakob & Hanika 2019) and taken at lambda.
// Directions and pdfs do not depend on colour, so only dispersive glass samples differently. Values are
// scalars; BsdfSample::f carries the value in all three channels.
#pragma once

#include <nimbus/cpp/math.hpp>
#include <nimbus/cpp/spectral.hpp>
#include "core/ior_curve.hpp"
#include "materials/bsdf.hpp"

namespace nimbus {

class SpectralBsdf {
 public:
  // `rgb`: the material's BSDF where the path is (textures applied); `dispersion`: its index over
  // wavelength when it is a dispersive dielectric, else null (a dielectric keeps its constant index);
  // lambda in nm. A lambda outside the visible range gives no value and no sample.
  SpectralBsdf(const Bsdf &rgb, const IorCurve *dispersion, float lambda);

  float eval(const Vec3f &wo, const Vec3f &wi, TransportMode mode, float *pdf_fwd = nullptr,
             float *pdf_rev = nullptr) const;
  BsdfSample sample(const Vec3f &wo, float uc, Vec2f u, TransportMode mode) const;
  float pdf(const Vec3f &wo, const Vec3f &wi, TransportMode mode) const;

  float lambda() const { return lambda_; }
  // The BSDF that does the scattering: the dielectric at lambda, or the RGB one whose values are uplifted.
  const Bsdf &bsdf() const { return bsdf_; }

 private:
  float value(const Rgb &f) const;

  Bsdf bsdf_;
  float lambda_;
  bool valid_;  // lambda is a visible wavelength
  bool grey_;   // a dielectric: its values are equal in all channels, nothing to uplift
};

}  // namespace nimbus
