// BSDFs in the local shading frame (z = shading normal), as value types. The host's BSDF service
// (abi/) converts world-space directions and applies the shading-normal corrections; integrators never
// see these classes.
//
// Conventions (shared with sdk/include/nimbus/bsdf.h): directions point away from the surface and are
// unit length; f excludes the cosine; pdfs are solid-angle; a delta lobe returns pdf = 1 and f = weight /
// |cos wi| from sample() and contributes nothing to eval()/pdf().
#pragma once

#include <cstdint>
#include <variant>

#include <nimbus/cpp/math.hpp>
#include "materials/conductor.hpp"
#include "materials/dielectric.hpp"
#include "materials/diffuse.hpp"
#include "materials/scattering.hpp"

namespace nimbus {

struct MaterialDesc;

class Bsdf {
 public:
  Bsdf() = default;
  template <class T>
  Bsdf(T impl) : impl_(impl) {}

  Rgb eval(const Vec3f &wo, const Vec3f &wi, TransportMode mode, float *pdf_fwd = nullptr,
           float *pdf_rev = nullptr) const {
    return std::visit([&](const auto &b) { return b.eval(wo, wi, mode, pdf_fwd, pdf_rev); }, impl_);
  }
  // uc selects a lobe, u picks the direction inside it.
  BsdfSample sample(const Vec3f &wo, float uc, Vec2f u, TransportMode mode) const {
    return std::visit([&](const auto &b) { return b.sample(wo, uc, u, mode); }, impl_);
  }
  float pdf(const Vec3f &wo, const Vec3f &wi, TransportMode mode) const {
    return std::visit([&](const auto &b) { return b.pdf(wo, wi, mode); }, impl_);
  }
  uint32_t lobes() const {
    return std::visit([](const auto &b) { return b.lobes(); }, impl_);
  }
  // Smallest GGX alpha among the lobes: 0 for delta, 1 for diffuse.
  float min_alpha() const {
    return std::visit([](const auto &b) { return b.min_alpha(); }, impl_);
  }
  // Directional-hemispherical reflectance (estimate) for the albedo element.
  Rgb albedo(const Vec3f &wo) const {
    return std::visit([&](const auto &b) { return b.albedo(wo); }, impl_);
  }
  // The dielectric this BSDF is, or null: paths that carry a wavelength rebuild it with their index.
  const DielectricBsdf *dielectric() const { return std::get_if<DielectricBsdf>(&impl_); }
  // The diffuse BSDF this is, or null (the BSDF service evaluates it without a shading frame).
  const DiffuseBsdf *diffuse() const { return std::get_if<DiffuseBsdf>(&impl_); }

 private:
  std::variant<DiffuseBsdf, ConductorBsdf, DielectricBsdf> impl_;
};

// The BSDF a material has, with its constant albedo and roughness.
Bsdf make_bsdf(const MaterialDesc &material);
// The same with albedo and roughness given (by textures at a surface point; see textured_materials.hpp).
Bsdf make_bsdf(const MaterialDesc &material, const Rgb &albedo, float roughness);

}  // namespace nimbus
