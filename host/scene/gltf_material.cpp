// A scene material for a glTF object that names none. Nimbus has no metallic-roughness blend, so the
// glTF material becomes one of its own types, chosen by the dominant lobe:
//   metallicFactor > 0.5  ->  conductor, ideal-mirror form: reflectance = baseColorFactor,
//                             roughness = roughnessFactor
//   otherwise             ->  diffuse: albedo = baseColorFactor (or its baseColorTexture, when that is an
//                             external image file); roughness is ignored
// Colours are clamped to [0, 1] like written ones. The material is named after the glTF material (or
// "<file>#<index>" when it has no name), made unique against the scene's names by a "-2", "-3", ... suffix.
#include <algorithm>
#include <filesystem>
#include <string>

#include "scene/sections.hpp"

namespace nimbus::scene_yaml {

namespace {

bool name_taken(const std::vector<MaterialDesc> &materials, const std::string &name) {
  return std::any_of(materials.begin(), materials.end(),
                     [&](const MaterialDesc &m) { return m.name == name; });
}

Rgb unit_clamped(const Rgb &c) {
  return {std::clamp(c.x, 0.0f, 1.0f), std::clamp(c.y, 0.0f, 1.0f), std::clamp(c.z, 0.0f, 1.0f)};
}

}  // namespace

uint32_t gltf_material(const GltfMaterial &g, const LoadedMesh &mesh, const YamlValue &where,
                       ObjectContext &context) {
  const std::string key = mesh.file + "#" + std::to_string(g.index);
  if (auto it = context.gltf_materials.find(key); it != context.gltf_materials.end()) return it->second;

  MaterialDesc mat;
  const std::string base =
      g.name.empty() ? std::filesystem::path(mesh.file).filename().string() + "#" + std::to_string(g.index)
                     : g.name;
  mat.name = base;
  for (int suffix = 2; name_taken(context.materials, mat.name); ++suffix)
    mat.name = base + "-" + std::to_string(suffix);
  mat.where = where.location();
  if (g.metallic > 0.5f) {
    mat.type = MaterialType::Conductor;
    mat.use_reflectance = true;
    mat.reflectance = unit_clamped(g.base_color);
    mat.roughness = std::clamp(g.roughness, 0.0f, 1.0f);
  } else {
    mat.type = MaterialType::Diffuse;
    mat.albedo = unit_clamped(g.base_color);
    if (!g.base_color_texture.empty()) {
      mat.albedo_texture.path = g.base_color_texture;
      mat.albedo_texture.key = where.path();
      mat.albedo_texture.where = where.location();
    }
  }
  const auto index = uint32_t(context.materials.size());
  context.materials.push_back(std::move(mat));
  context.gltf_materials.emplace(key, index);
  return index;
}

}  // namespace nimbus::scene_yaml
