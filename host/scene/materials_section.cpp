// `materials:` — a map from name to {type: diffuse | conductor | dielectric, ...}. A dielectric's index of
// refraction (ior, or a dispersive abbe, cauchy or sellmeier curve) is read by dielectric_section.cpp.
//
// Textures. A constant can be replaced by an image file, read through OpenImageIO (EXR, HDR, PNG, JPEG,
// TIFF, ...) when the scene is built; a missing or unreadable file is an error naming it and the reason.
//
//   floor:  { type: diffuse, albedo: { texture: assets/wood.png } }          # or albedo: [r, g, b]
//   steel:  { type: conductor, metal: iron, roughness: { texture: r.exr } }  # or roughness: 0.3
//   tiles:  { type: diffuse, albedo: { texture: t.jpg }, normal_map: maps/n.png, uv_scale: [4, 4] }
//
//   albedo: { texture: PATH }     diffuse only. Colour: files stored as 8- or 16-bit integers (PNG, JPEG)
//                                 are sRGB-encoded and decoded to linear; float files (EXR, HDR) are
//                                 linear. One channel is grey; a fourth (alpha) is ignored. Clamped to
//                                 [0, 1] like the constant: more would reflect more light than arrives.
//   roughness: { texture: PATH }  conductor and dielectric. The first channel, as data (no decoding),
//                                 clamped to [0, 1]; same meaning as the number it replaces.
//   normal_map: PATH              any type (also written { texture: PATH }). Tangent-space normals as data,
//                                 n = 2 rgb - 1, OpenGL convention: red = +u (along dpdu), green = +v (up
//                                 in the image), blue = out of the surface; (0.5, 0.5, 1) changes nothing.
//   uv_scale: [su, sv] or s       > 0; the texture repeats su times along u and sv times along v. Only
//                                 with a texture (otherwise it would be silently ignored).
//
// Paths are relative to the file that names them. A surface point (u, v) reads the image at (u su, v sv),
// repeating periodically, with v = 0 at the bottom row of the image (the OBJ convention): an image on a
// `rectangle` reads upright seen from its front with +y up. Filtering is bilinear on the finest level
// (colour decoded before filtering); the progressive loop's pixel jitter integrates the pixel footprint.
#include <filesystem>
#include <string>
#include <vector>

#include "scene/metals.hpp"
#include "scene/sections.hpp"

namespace nimbus::scene_yaml {

namespace {

const Range kUnit = Range::closed(0, 1);

// The image file a scalar names, resolved against the directory of the file that names it.
TextureDesc texture_file(const YamlValue &file) {
  TextureDesc t;
  // Absolute, so that errors name the file unambiguously whatever the working directory.
  const std::filesystem::path path = file.source().resolve(file.nonempty_string());
  std::error_code ec;
  const std::filesystem::path absolute = std::filesystem::absolute(path, ec);
  t.path = (ec ? path : absolute).lexically_normal().string();
  t.key = file.path();
  t.where = file.location();
  return t;
}

// `{ texture: PATH }`
TextureDesc read_texture(const YamlValue &v) { return texture_file(v.map({"texture"}).require("texture")); }

// Keys every material type accepts besides its own; after those, so that uv_scale knows of all textures.
void read_common(const YamlMap &m, MaterialDesc &mat) {
  if (auto v = m.get("normal_map")) mat.normal_map = v->is_map() ? read_texture(*v) : texture_file(*v);
  if (auto v = m.get("uv_scale")) {
    if (!mat.textured()) m.key("uv_scale").fail("needs a texture (albedo, roughness or normal_map) to scale");
    if (v->is_sequence()) {
      mat.uv_scale = v->vec2(Range::greater_than(0));
    } else {
      const float scale = v->real(Range::greater_than(0));
      mat.uv_scale = {scale, scale};
    }
  }
}

void read_roughness(const YamlMap &m, MaterialDesc &mat) {
  if (auto v = m.get("roughness")) {
    if (v->is_map())
      mat.roughness_texture = read_texture(*v);
    else
      mat.roughness = v->real(kUnit);
  }
}

void read_diffuse(const YamlMap &m, MaterialDesc &mat) {
  m.check_keys({"type", "albedo", "normal_map", "uv_scale"}, "a diffuse material");
  if (auto v = m.get("albedo")) {
    if (v->is_map())
      mat.albedo_texture = read_texture(*v);
    else
      mat.albedo = v->rgb(kUnit);
  }
}

std::string known_metals() {
  std::vector<std::string_view> names;
  for (const MetalIor &metal : kMetals) names.push_back(metal.name);
  return join_names(names);
}

// A conductor is described exactly one way: a named metal, a complex IOR (eta and k together), or an ideal
// mirror's reflectance. Mixing them would leave one silently ignored, so it is an error.
void read_conductor(const YamlMap &m, MaterialDesc &mat) {
  m.check_keys({"type", "metal", "eta", "k", "reflectance", "roughness", "normal_map", "uv_scale"},
               "a conductor");
  const auto form_of = [](const std::string &key) -> std::string_view {
    if (key == "eta" || key == "k") return "eta";
    if (key == "metal" || key == "reflectance") return key;
    return {};
  };
  const YamlMap::Entry *first = nullptr;  // the key that chose the form
  for (const YamlMap::Entry &e : m.entries()) {
    const std::string_view form = form_of(e.key);
    if (form.empty()) continue;
    if (!first)
      first = &e;
    else if (form_of(first->key) != form)
      e.key_value.fail("conflicts with '" + first->key + "'; give one of metal, eta and k, or reflectance");
  }
  if (!first) m.self().fail("a conductor needs 'metal', 'eta' and 'k', or 'reflectance'");

  if (auto v = m.get("metal")) {
    const std::string name = v->string();
    const std::optional<MetalIor> metal = find_metal(name);
    if (!metal) v->fail("unknown metal '" + abbreviate(name) + "'; known: " + known_metals());
    mat.eta = metal->eta;
    mat.k = metal->k;
  }
  if (m.has("eta") || m.has("k")) {
    mat.eta = m.require("eta").rgb(Range::greater_than(0));
    mat.k = m.require("k").rgb(Range::at_least(0));
  }
  if (auto v = m.get("reflectance")) {
    mat.use_reflectance = true;
    mat.reflectance = v->rgb(kUnit);
  }
  read_roughness(m, mat);
}

void read_dielectric(const YamlMap &m, MaterialDesc &mat) {
  m.check_keys({"type", "ior", "abbe", "cauchy", "sellmeier", "roughness", "normal_map", "uv_scale"},
               "a dielectric");
  read_dielectric_index(m, mat);
  read_roughness(m, mat);
}

}  // namespace

std::vector<MaterialDesc> read_materials(const YamlValue &section) {
  std::vector<MaterialDesc> out;
  if (section.is_null()) return out;
  const YamlMap materials = section.map();  // named: the loop below borrows its entries
  for (const YamlMap::Entry &e : materials.entries()) {
    if (e.key.empty()) e.key_value.fail("material names must not be empty");
    const YamlMap m = e.value.map();
    MaterialDesc mat;
    mat.name = e.key;
    mat.where = e.value.location();
    const YamlValue type = m.require("type");
    const std::string name = type.string();
    if (name == "diffuse") {
      mat.type = MaterialType::Diffuse;
      read_diffuse(m, mat);
    } else if (name == "conductor") {
      mat.type = MaterialType::Conductor;
      read_conductor(m, mat);
    } else if (name == "dielectric") {
      mat.type = MaterialType::Dielectric;
      read_dielectric(m, mat);
    } else {
      type.fail("unknown material type '" + abbreviate(name) + "'; known: diffuse, conductor, dielectric");
    }
    read_common(m, mat);
    out.push_back(std::move(mat));
  }
  return out;
}

}  // namespace nimbus::scene_yaml
