// Scene materials made from the materials a mesh file brings (glTF, OBJ's .mtl): shared by the objects
// that use the same file, and named so that they never clash with the scene's own.
#include <algorithm>
#include <string>

#include "scene/sections.hpp"

namespace nimbus::scene_yaml {

uint32_t add_file_material(const std::string &key, MaterialDesc material, ObjectContext &context) {
  if (auto it = context.file_materials.find(key); it != context.file_materials.end()) return it->second;
  const auto taken = [&](const std::string &name) {
    return std::any_of(context.materials.begin(), context.materials.end(),
                       [&](const MaterialDesc &m) { return m.name == name; });
  };
  const std::string base = material.name;
  for (int suffix = 2; taken(material.name); ++suffix) material.name = base + "-" + std::to_string(suffix);
  const auto index = uint32_t(context.materials.size());
  context.materials.push_back(std::move(material));
  context.file_materials.emplace(key, index);
  return index;
}

Rgb unit_clamped(const Rgb &color) { return min(max(color, Rgb(0.0f)), Rgb(1.0f)); }

}  // namespace nimbus::scene_yaml
