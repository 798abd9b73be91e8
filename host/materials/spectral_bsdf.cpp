#include "materials/spectral_bsdf.hpp"

#include "core/rgb_uplift_table.hpp"

namespace nimbus {

namespace {

Bsdf at_wavelength(const Bsdf &rgb, const IorCurve *dispersion, float lambda) {
  const DielectricBsdf *glass = rgb.dielectric();
  if (glass && dispersion) return glass->with_eta(dispersion->at(lambda));
  return rgb;
}

}  // namespace

SpectralBsdf::SpectralBsdf(const Bsdf &rgb, const IorCurve *dispersion, float lambda)
    : bsdf_(at_wavelength(rgb, dispersion, lambda)),
      lambda_(lambda),
      valid_(lambda >= kLambdaMin && lambda <= kLambdaMax),
      grey_(rgb.dielectric() != nullptr) {}

float SpectralBsdf::value(const Rgb &f) const { return grey_ ? f.x : uplift(f, lambda_); }

float SpectralBsdf::eval(const Vec3f &wo, const Vec3f &wi, TransportMode mode, float *pdf_fwd,
                         float *pdf_rev) const {
  if (!valid_) {
    if (pdf_fwd) *pdf_fwd = 0;
    if (pdf_rev) *pdf_rev = 0;
    return 0;
  }
  return value(bsdf_.eval(wo, wi, mode, pdf_fwd, pdf_rev));
}

BsdfSample SpectralBsdf::sample(const Vec3f &wo, float uc, Vec2f u, TransportMode mode) const {
  if (!valid_) return {};
  BsdfSample s = bsdf_.sample(wo, uc, u, mode);
  if (s.pdf > 0) s.f = Rgb(value(s.f));
  return s;
}

float SpectralBsdf::pdf(const Vec3f &wo, const Vec3f &wi, TransportMode mode) const {
  return valid_ ? bsdf_.pdf(wo, wi, mode) : 0.0f;
}

}  // namespace nimbus
