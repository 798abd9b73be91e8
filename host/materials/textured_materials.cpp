#include "materials/textured_materials.hpp"

#include <algorithm>
#include <atomic>
#include <cstring>

#include "materials/normal_map.hpp"

namespace nimbus {

namespace {
std::atomic<uint64_t> next_instance{1};
}  // namespace

Expected<std::unique_ptr<TexturedMaterials>> TexturedMaterials::build(
    const std::vector<MaterialDesc> &materials) {
  if (std::none_of(materials.begin(), materials.end(), [](const MaterialDesc &m) { return m.textured(); }))
    return std::unique_ptr<TexturedMaterials>();
  auto set = std::make_unique<TexturedMaterials>();
  set->instance_ = next_instance.fetch_add(1);
  set->materials_ = materials;
  set->bindings_.resize(materials.size());
  for (size_t i = 0; i < materials.size(); ++i) {
    const MaterialDesc &m = materials[i];
    Binding &b = set->bindings_[i];
    b.any = m.textured();
    const auto add = [&](const TextureDesc &t, TextureSet::Kind kind, int channels,
                         TextureSet::Id &id) -> Status {
      if (t.empty()) return Ok{};
      auto added = set->textures_.add(t, kind, channels);
      if (!added) return added.error();
      id = added.value();
      return Ok{};
    };
    if (Status s = add(m.albedo_texture, TextureSet::Kind::Color, 1, b.albedo); !s) return s.error();
    if (Status s = add(m.roughness_texture, TextureSet::Kind::Data, 1, b.roughness); !s) return s.error();
    if (Status s = add(m.normal_map, TextureSet::Kind::Data, 3, b.normal); !s) return s.error();
  }
  return set;
}

Bsdf TexturedMaterials::bsdf(uint64_t material, Vec2f uv) const {
  const MaterialDesc &m = materials_[material];
  const Binding &b = bindings_[material];
  const Vec2f st = texture_coordinates(uv, m.uv_scale);
  // Clamped: filtering cannot leave [0, 1] but an EXR can hold anything, and albedo > 1 creates energy.
  const Rgb albedo = b.albedo == kNone ? m.albedo : min(max(textures_.rgb(b.albedo, st), Rgb(0)), Rgb(1));
  const float roughness = b.roughness == kNone ? m.roughness : clamp(textures_.scalar(b.roughness, st), 0, 1);
  return make_bsdf(m, albedo, roughness);
}

Vec3f TexturedMaterials::shading_normal(uint64_t material, Vec2f uv, const Vec3f &ns, const Vec3f &ng,
                                        const Vec3f &dpdu, const Vec3f &dpdv) const {
  const Vec2f st = texture_coordinates(uv, materials_[material].uv_scale);
  const Vec3f m = decode_normal(textures_.rgb(bindings_[material].normal, st));
  return apply_normal_map(m, ns, ng, dpdu, dpdv);
}

TexturedMaterials::Shading TexturedMaterials::shade(uint64_t material, const SurfacePoint &p) const {
  struct Last {
    uint64_t owner = 0, material = 0;
    SurfacePoint point;
    Shading shading;
  };
  thread_local Last last;
  static_assert(sizeof(SurfacePoint) == 14 * sizeof(float), "compared bitwise: no padding");
  if (last.owner == instance_ && last.material == material && std::memcmp(&last.point, &p, sizeof(p)) == 0)
    return last.shading;
  Shading s{bsdf(material, p.uv), p.ns, false};
  if (has_normal_map(material)) {
    s.ns = shading_normal(material, p.uv, p.ns, p.ng, p.dpdu, p.dpdv);
    s.normal_mapped = true;
  }
  last = {instance_, material, p, s};
  return s;
}

}  // namespace nimbus
