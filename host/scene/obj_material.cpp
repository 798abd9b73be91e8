// Scene materials and emission for an OBJ object that names no material, from the .mtl materials its
// faces use. Nimbus has no Phong mix of diffuse, specular and transmitted light, so each .mtl material
// becomes the one of Nimbus's types whose lobe dominates, tested in this order:
//   transmission: illum 4, 6 or 7; d < 1 (or Tr > 0 when there is no d); or Tf below 1 and not black
//       -> dielectric: ior = Ni (1.5 when absent or <= 1, which no glass has), roughness from Ns
//   specular: illum 3 (mirror), or Ks outweighs Kd in luminance
//       -> conductor, ideal-mirror form: reflectance = Ks, roughness from Ns
//   otherwise
//       -> diffuse: albedo = Kd (0.8 when absent), or the map_Kd image (which then replaces Kd)
// Roughness: the Phong exponent Ns corresponds to the GGX alpha = sqrt(2 / (Ns + 2)) (Walter et al. 2007),
// and Nimbus's roughness r has alpha = r^2; without Ns the surface is smooth (r = 0). Ke > 0 makes the
// faces an area light of radiance Ke. Ka is ignored: ambient light has no physical meaning here. Colours
// are clamped to [0, 1] like written ones (Ke only to >= 0). Faces without a `usemtl` that names a
// material get a diffuse 0.8 named "<file>#default". The materials are named after the .mtl ones, made
// unique against the scene's names by a "-2", "-3", ... suffix.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include "core/one_line.hpp"
#include "scene/mesh_builders.hpp"
#include "scene/sections.hpp"

namespace nimbus::scene_yaml {

namespace {

constexpr Rgb kDefaultAlbedo{0.8f, 0.8f, 0.8f};

float roughness_from_phong(const std::optional<float> &ns) {
  if (!ns) return 0;
  const float alpha = std::sqrt(2 / (std::max(*ns, 0.0f) + 2));
  return std::clamp(std::sqrt(alpha), 0.0f, 1.0f);
}

bool transmits(const MtlMaterial &m) {
  if (m.illum == 4 || m.illum == 6 || m.illum == 7) return true;
  if (m.d ? *m.d < 1 : m.tr && *m.tr > 0) return true;  // `d` wins: exporters disagree on what Tr means
  // Tf filters the light that passes; a black filter passes none, and many exporters write a white one
  // on every opaque material.
  return m.tf && std::min({m.tf->x, m.tf->y, m.tf->z}) < 1 && max_component(*m.tf) > 0;
}

MaterialDesc scene_material(const MtlMaterial &m) {
  MaterialDesc mat;
  mat.name = m.name;
  const Rgb albedo = m.kd ? unit_clamped(*m.kd) : kDefaultAlbedo;
  const Rgb specular = m.ks ? unit_clamped(*m.ks) : Rgb(0.0f);
  if (transmits(m)) {
    mat.type = MaterialType::Dielectric;
    mat.ior = m.ni && *m.ni > 1 ? std::min(*m.ni, 10.0f) : 1.5f;  // [1, 10], as written ones
    mat.roughness = roughness_from_phong(m.ns);
  } else if (m.illum == 3 || luminance(specular) > luminance(albedo)) {
    mat.type = MaterialType::Conductor;
    mat.use_reflectance = true;
    mat.reflectance = specular;
    mat.roughness = roughness_from_phong(m.ns);
  } else {
    mat.type = MaterialType::Diffuse;
    mat.albedo = albedo;
    mat.albedo_texture.path = m.map_kd;
  }
  return mat;
}

// "a, b, c", cut after a dozen: a file of junk must not make a warning of thousands of words.
std::string listed(const std::vector<std::string> &items) {
  constexpr size_t kMax = 12;
  std::string out;
  for (size_t i = 0; i < items.size() && i < kMax; ++i) out += (i ? ", " : "") + shown(items[i]);
  if (items.size() > kMax) out += " and " + std::to_string(items.size() - kMax) + " more";
  return out;
}

// One warning per file, however many objects use it: the .mtl statements not mapped, and `usemtl` names
// no .mtl file defines.
void warn_once(const LoadedMesh &mesh, const YamlValue &where, ObjectContext &context) {
  const ObjMaterials &obj = mesh.obj_materials;
  for (const ObjMaterials::File &file : obj.files)
    if (!file.ignored.empty() && context.warned.insert(file.path).second)
      context.warnings.push_back(where.warning(
          file.path + ": ignores the .mtl statements Nimbus does not map: " + listed(file.ignored)));
  if (!obj.unknown.empty() && context.warned.insert(mesh.file).second)
    context.warnings.push_back(where.warning(mesh.file +
                                             ": usemtl names materials no .mtl file defines (their faces get "
                                             "the default material): " +
                                             listed(obj.unknown)));
}

uint32_t part_material(const ObjPart &part, const LoadedMesh &mesh, const YamlValue &where,
                       ObjectContext &context) {
  MaterialDesc mat;
  if (part.material >= 0) {
    mat = scene_material(mesh.obj_materials.materials[size_t(part.material)]);
  } else {
    mat.name = std::filesystem::path(mesh.file).filename().string() + "#default";
    mat.albedo = kDefaultAlbedo;
  }
  mat.where = where.location();
  if (!mat.albedo_texture.empty())
    mat.albedo_texture.key = where.path(), mat.albedo_texture.where = mat.where;
  return add_file_material(mesh.file + "#" + std::to_string(part.material), std::move(mat), context);
}

}  // namespace

std::vector<ShapeDesc> obj_material_shapes(ShapeDesc shape, const LoadedMesh &mesh, const YamlMap &object,
                                           const YamlValue &where, ObjectContext &context) {
  const ObjMaterials &obj = mesh.obj_materials;
  if (!obj.error.empty())
    where.fail("cannot use the materials of '" + mesh.file + "': " + obj.error +
               " (an object with 'material:' needs none)");
  warn_once(mesh, where, context);
  const MeshData all = std::move(shape.mesh);
  std::vector<ShapeDesc> shapes;
  for (const ObjPart &part : mesh.parts) {
    ShapeDesc s = shape;
    s.material = part_material(part, mesh, where, context);
    const MtlMaterial *m = part.material >= 0 ? &obj.materials[size_t(part.material)] : nullptr;
    // The object's own `emission:` applies to all its faces, as to any object.
    if (m && m->ke && !object.has("emission") && !is_black(max(*m->ke, Rgb(0.0f)))) {
      const std::string why = ": its .mtl material '" + shown(m->name) + "' emits (Ke)";
      if (object.has("motion")) object.key("motion").fail("an emitting object cannot move yet" + why);
      if (object.has("deform")) object.key("deform").fail("an emitting mesh cannot deform yet" + why);
      s.emission = max(*m->ke, Rgb(0.0f));
    }
    s.mesh = submesh(all, part.triangles);
    shapes.push_back(std::move(s));
  }
  return shapes;
}

}  // namespace nimbus::scene_yaml
