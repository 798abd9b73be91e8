// `materials:` — a map from name to {type: diffuse | conductor | dielectric, ...}.
#include <string>
#include <vector>

#include "materials/metals.hpp"
#include "scene/sections.hpp"

namespace nimbus::scene_yaml {

namespace {

const Range kUnit = Range::closed(0, 1);

void read_diffuse(const YamlMap &m, MaterialDesc &mat) {
  m.check_keys({"type", "albedo"}, "a diffuse material");
  if (auto v = m.get("albedo")) mat.albedo = v->rgb(kUnit);
}

std::string known_metals() {
  std::vector<std::string_view> names;
  for (const MetalIor &metal : kMetals) names.push_back(metal.name);
  return join_names(names);
}

// A conductor is described exactly one way: a named metal, a complex IOR (eta and k together), or an ideal
// mirror's reflectance. Mixing them would leave one silently ignored, so it is an error.
void read_conductor(const YamlMap &m, MaterialDesc &mat) {
  m.check_keys({"type", "metal", "eta", "k", "reflectance", "roughness"}, "a conductor");
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
  if (auto v = m.get("roughness")) mat.roughness = v->real(kUnit);
}

void read_dielectric(const YamlMap &m, MaterialDesc &mat) {
  m.check_keys({"type", "ior", "roughness"}, "a dielectric");
  // Relative IORs below 1 (e.g. an air bubble in water) need nested media, which v0 does not model.
  if (auto v = m.get("ior")) mat.ior = v->real(Range::closed(1, 10));
  if (auto v = m.get("roughness")) mat.roughness = v->real(kUnit);
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
    out.push_back(std::move(mat));
  }
  return out;
}

}  // namespace nimbus::scene_yaml
