// Lambertian reflection, lit from either side (a single-sided plane seen from behind still reflects).
#pragma once

#include <cstdint>

#include <nimbus/cpp/math.hpp>
#include "materials/scattering.hpp"

namespace nimbus {

class DiffuseBsdf {
 public:
  // The default matches MaterialDesc's, so a default Bsdf equals make_bsdf(MaterialDesc{}).
  DiffuseBsdf() = default;
  explicit DiffuseBsdf(const Rgb &albedo) : albedo_(albedo) {}

  Rgb eval(const Vec3f &wo, const Vec3f &wi, TransportMode mode, float *pdf_fwd, float *pdf_rev) const;
  BsdfSample sample(const Vec3f &wo, float uc, Vec2f u, TransportMode mode) const;
  float pdf(const Vec3f &wo, const Vec3f &wi, TransportMode mode) const;
  uint32_t lobes() const { return NIMBUS_LOBE_REFLECTION | NIMBUS_LOBE_DIFFUSE; }
  float min_alpha() const { return 1; }
  Rgb albedo(const Vec3f &) const { return albedo_; }

 private:
  Rgb albedo_{0.8f, 0.8f, 0.8f};
};

}  // namespace nimbus
