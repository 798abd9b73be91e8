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

uint32_t gltf_material(const GltfMaterial &g, const LoadedMesh &mesh, const YamlValue &where,
                       ObjectContext &context) {
  MaterialDesc mat;
  mat.name = g.name.empty()
                 ? std::filesystem::path(mesh.file).filename().string() + "#" + std::to_string(g.index)
                 : g.name;
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
  return add_file_material(mesh.file + "#" + std::to_string(g.index), std::move(mat), context);
}

}  // namespace nimbus::scene_yaml
