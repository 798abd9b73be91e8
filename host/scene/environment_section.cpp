// `environment:` — radiance from infinitely far away, written one of three ways:
//   { color: [r, g, b] }                      uniform
//   { map: sky.exr, scale: 1, rotate: 90 }    lat-long image (radiance), rotated about +z
//   { type: sky, turbidity: 3, scale: 1 }     Preetham sky; its sun is the scene's sun light, or
//                                             `sun_direction:` (towards the sun) when there is none
// The form is decided by the keys written, and every key must belong to that form: a `rotate:` next to a
// colour or a `turbidity:` next to a map would be silently ignored otherwise.
#include <filesystem>
#include <string>

#include "scene/sections.hpp"

namespace nimbus::scene_yaml {

namespace {

// The form named by `type:` (color | map | sky) or, without it, by the one of `color:`/`map:` present.
EnvironmentType read_form(const YamlMap &m) {
  if (m.has("color") && m.has("map")) m.key("map").fail("cannot be combined with 'color'");
  EnvironmentType from_keys = m.has("color") ? EnvironmentType::Color
                              : m.has("map") ? EnvironmentType::Map
                                             : EnvironmentType::None;
  auto type = m.get("type");
  if (!type) {
    if (from_keys == EnvironmentType::None)
      m.self().fail("expected { color: [r, g, b] }, { map: FILE } or { type: sky }");
    return from_keys;
  }
  const std::string name = type->string();
  const EnvironmentType named = name == "color" ? EnvironmentType::Color
                                : name == "map" ? EnvironmentType::Map
                                : name == "sky" ? EnvironmentType::Sky
                                                : EnvironmentType::None;
  if (named == EnvironmentType::None)
    type->fail("unknown environment type '" + abbreviate(name) + "'; known: color, map, sky");
  if (named == EnvironmentType::Sky && from_keys != EnvironmentType::None)
    m.key(from_keys == EnvironmentType::Color ? "color" : "map").fail("cannot be combined with type sky");
  if (named != EnvironmentType::Sky && from_keys != named) (void)m.require(name);
  return named;
}

// The file must exist now: a typo found after minutes of scene building is a worse error than one now.
// The image itself is read when the scene is built (host/lights/environment_map.cpp).
std::string read_map_path(const YamlValue &v) {
  const std::filesystem::path path = v.source().resolve(v.nonempty_string());
  std::error_code ec;
  const std::filesystem::path absolute = std::filesystem::absolute(path, ec);
  const std::string shown = path.string();
  if (!std::filesystem::exists(path, ec)) v.fail("environment map '" + shown + "' does not exist");
  if (std::filesystem::is_directory(path, ec)) v.fail("environment map '" + shown + "' is a directory");
  return (ec ? path : absolute).lexically_normal().string();
}

// The sky's sun: the scene's sun light when it has exactly one, otherwise `sun_direction:`.
void read_sky_sun(const YamlMap &m, const std::vector<LightDesc> &lights, EnvironmentDesc &env) {
  std::vector<const LightDesc *> suns;
  for (const LightDesc &l : lights)
    if (l.type == LightType::Sun) suns.push_back(&l);
  if (suns.size() > 1)
    m.self().fail("a sky takes its sun from the scene's sun light, but there are " +
                  std::to_string(suns.size()) + " (at " + suns[0]->where.text() + " and " +
                  suns[1]->where.text() + ")");
  if (suns.size() == 1) {
    if (m.has("sun_direction"))
      m.key("sun_direction")
          .fail("cannot be combined with the sun light at " + suns[0]->where.text() +
                ", which sets the sky's sun");
    env.sun_direction = -suns[0]->direction;
    return;
  }
  const YamlValue v = m.require("sun_direction");
  const Vec3f d = v.vec3();
  if (!(length(d) > 0)) v.fail("must not be the zero vector");
  env.sun_direction = normalize(d);
}

}  // namespace

EnvironmentDesc read_environment(const YamlValue &section, const std::vector<LightDesc> &lights) {
  EnvironmentDesc env;
  if (section.is_null()) return env;  // `environment:` with nothing under it: none
  env.where = section.location();
  const YamlMap m = section.map();
  env.type = read_form(m);
  switch (env.type) {
    case EnvironmentType::Color:
      m.check_keys({"type", "color", "scale", "group"}, "a uniform environment");
      env.color = m.require("color").rgb(Range::at_least(0));
      break;
    case EnvironmentType::Map:
      m.check_keys({"type", "map", "scale", "rotate", "group"}, "an environment map");
      env.map = read_map_path(m.require("map"));
      if (auto v = m.get("rotate")) env.rotate_degrees = v->real();
      break;
    case EnvironmentType::Sky:
      m.check_keys({"type", "turbidity", "sun_direction", "scale", "group"}, "a sky");
      if (auto v = m.get("turbidity")) env.turbidity = v->real(Range::closed(1.7, 10));
      read_sky_sun(m, lights, env);
      break;
    case EnvironmentType::None:
      break;
  }
  if (auto v = m.get("scale")) env.scale = v->real(Range::at_least(0));
  if (auto v = m.get("group")) env.group = v->string();
  return env;
}

}  // namespace nimbus::scene_yaml
