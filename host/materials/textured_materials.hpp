// Materials whose parameters vary over the surface. Their BSDF is built at each surface point from texture
// lookups at its (u, v); materials without textures never come here and keep the BSDF built once with the
// scene, so a scene without textures pays nothing, not even for opening the texture system.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <nimbus/cpp/math.hpp>
#include "core/expected.hpp"
#include "materials/bsdf.hpp"
#include "materials/texture_set.hpp"
#include "scene/scene_desc.hpp"

namespace nimbus {

class TexturedMaterials {
 public:
  // Opens and validates every texture the materials name; null when none names any.
  static Expected<std::unique_ptr<TexturedMaterials>> build(const std::vector<MaterialDesc> &materials);

  bool textured(uint64_t material) const { return material < bindings_.size() && bindings_[material].any; }
  // Whether the material's lobes and min alpha depend on the point: only a roughness texture changes them.
  bool varies_lobes(uint64_t material) const {
    return textured(material) && bindings_[material].roughness != kNone;
  }
  bool has_normal_map(uint64_t material) const {
    return textured(material) && bindings_[material].normal != kNone;
  }

  // A surface point as shading sees it: world space, ns and ng unit and on the same side.
  struct SurfacePoint {
    Vec3f ng, ns, dpdu, dpdv;
    Vec2f uv;
  };
  struct Shading {
    Bsdf bsdf;
    Vec3f ns;  // the normal the BSDF's frame is built on
    bool normal_mapped = false;
  };
  // bsdf() and shading_normal() at p, for a textured material. The last result is kept per thread:
  // integrators ask several questions at one vertex (lobes, sample, eval towards a light sample), and
  // texture lookups cost far more than comparing the point.
  Shading shade(uint64_t material, const SurfacePoint &p) const;

  // The material's BSDF at surface coordinates uv (a textured material).
  Bsdf bsdf(uint64_t material, Vec2f uv) const;
  // The shading normal after the material's normal map (one that has_normal_map), in world space: ns tilted
  // in the frame (dpdu, dpdv, ns) and kept on ng's side (normal_map.hpp).
  Vec3f shading_normal(uint64_t material, Vec2f uv, const Vec3f &ns, const Vec3f &ng, const Vec3f &dpdu,
                       const Vec3f &dpdv) const;

  // Texture coordinates of surface coordinates: scaled, and flipped in v because images store their top
  // row first while v = 0 is the bottom of a texture (the OBJ convention).
  static Vec2f texture_coordinates(Vec2f uv, Vec2f scale) { return {uv.x * scale.x, 1 - uv.y * scale.y}; }

 private:
  static constexpr TextureSet::Id kNone = ~TextureSet::Id(0);
  struct Binding {
    bool any = false;
    TextureSet::Id albedo = kNone, roughness = kNone, normal = kNone;
  };

  uint64_t instance_ = 0;                // never reused: keys the per-thread cache of shade()
  std::vector<MaterialDesc> materials_;  // the constants the textures do not replace
  std::vector<Binding> bindings_;        // one per material
  TextureSet textures_;
};

}  // namespace nimbus
