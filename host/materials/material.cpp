#include "materials/bsdf.hpp"
#include "scene/scene_desc.hpp"

namespace nimbus {

Bsdf make_bsdf(const MaterialDesc &material) {
  return make_bsdf(material, material.albedo, material.roughness);
}

Bsdf make_bsdf(const MaterialDesc &material, const Rgb &albedo, float roughness) {
  const float alpha = TrowbridgeReitz::roughness_to_alpha(roughness);
  switch (material.type) {
    case MaterialType::Diffuse:
      return DiffuseBsdf(albedo);
    case MaterialType::Conductor:
      return material.use_reflectance ? ConductorBsdf::mirror(material.reflectance, alpha)
                                      : ConductorBsdf::fresnel(material.eta, material.k, alpha);
    case MaterialType::Dielectric:
      return material.dispersive() ? DielectricBsdf::dispersive(material.ior, alpha)
                                   : DielectricBsdf(material.ior, alpha);
  }
  return DiffuseBsdf(albedo);  // unreachable for valid enum values
}

}  // namespace nimbus
