#include "materials/bsdf.hpp"
#include "scene/scene_desc.hpp"

namespace nimbus {

Bsdf make_bsdf(const MaterialDesc &material) {
  const float alpha = TrowbridgeReitz::roughness_to_alpha(material.roughness);
  switch (material.type) {
    case MaterialType::Diffuse:
      return DiffuseBsdf(material.albedo);
    case MaterialType::Conductor:
      return material.use_reflectance ? ConductorBsdf::mirror(material.reflectance, alpha)
                                      : ConductorBsdf::fresnel(material.eta, material.k, alpha);
    case MaterialType::Dielectric:
      return DielectricBsdf(material.ior, alpha);
  }
  return DiffuseBsdf(material.albedo);  // unreachable for valid enum values
}

}  // namespace nimbus
