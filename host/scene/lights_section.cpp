// `lights:` — a list of delta lights; v0 has point lights only.
#include "scene/sections.hpp"

namespace nimbus::scene_yaml {

namespace {

LightDesc read_light(const YamlValue &value) {
  const YamlMap m = value.map();
  const YamlValue type = m.require("type");
  const std::string name = type.string();
  if (name != "point") type.fail("unknown light type '" + abbreviate(name) + "'; known: point");
  m.check_keys({"type", "position", "intensity", "group"}, "a point light");

  LightDesc light;
  light.type = LightType::Point;
  light.where = value.location();
  light.position = m.require("position").vec3();
  if (auto v = m.get("intensity")) light.intensity = v->rgb(Range::at_least(0));
  if (auto v = m.get("group")) light.group = v->string();
  return light;
}

}  // namespace

std::vector<LightDesc> read_lights(const YamlValue &section) {
  std::vector<LightDesc> out;
  if (section.is_null()) return out;
  for (const YamlValue &light : section.sequence()) out.push_back(read_light(light));
  return out;
}

}  // namespace nimbus::scene_yaml
