// `lights:` — the delta and distant lights: point, spot and sun. Area lights are `emission:` on objects
// and the sky and environment maps are `environment:` (environment_section.cpp).
#include <cmath>
#include <string>

#include "scene/sections.hpp"

namespace nimbus::scene_yaml {

namespace {

const Range kNonNegative = Range::at_least(0);

// A direction only has to be non-zero; it is stored normalised.
Vec3f read_direction(const YamlValue &v) {
  const Vec3f d = v.vec3();
  if (!(length(d) > 0)) v.fail("must not be the zero vector");
  return normalize(d);
}

// `intensity:` (W/sr, rgb or grey) or `power:` (W, rgb or grey), never both: one would be silently ignored.
// `solid_angle` is the intensity-weighted solid angle the light emits into, so that power / solid_angle
// makes the light emit exactly `power` watts.
void read_intensity(const YamlMap &m, LightDesc &light, double solid_angle) {
  if (m.has("intensity") && m.has("power")) m.key("power").fail("cannot be combined with 'intensity'");
  if (auto v = m.get("intensity")) light.intensity = v->rgb(kNonNegative);
  if (auto v = m.get("power")) {
    const Rgb power = v->rgb(kNonNegative);
    for (int c = 0; c < 3; ++c) light.intensity[c] = float(double(power[c]) / solid_angle);
    if (!is_finite(light.intensity)) v->fail("the resulting intensity overflows");
  }
}

void read_point(const YamlMap &m, LightDesc &light) {
  m.check_keys({"type", "position", "intensity", "power", "group", "motion"}, "a point light");
  light.position = m.require("position").vec3();
  read_intensity(m, light, 4 * kPi);
}

// The cone is `cone` degrees from the axis; its smooth edge (a smoothstep in cos theta, as the host's
// SpotLight::falloff) spans the last `softness` degrees. Integrating that profile over the sphere gives
// the solid angle 2 pi (1 - (cos(cone - softness) + cos(cone)) / 2) that turns power into intensity.
void read_spot(const YamlMap &m, LightDesc &light) {
  m.check_keys({"type", "position", "direction", "cone", "softness", "intensity", "power", "group", "motion"},
               "a spot light");
  light.position = m.require("position").vec3();
  light.direction = read_direction(m.require("direction"));
  if (auto v = m.get("cone")) light.cone_degrees = v->real(Range{0, 180, true, false});
  // Default 5 degrees, narrowed for cones smaller than that rather than failing on a key not written.
  light.softness_degrees = std::min(5.0f, light.cone_degrees);
  if (auto v = m.get("softness")) light.softness_degrees = v->real(Range::closed(0, light.cone_degrees));
  const double cone = double(radians(light.cone_degrees));
  const double inner = cone - double(radians(light.softness_degrees));
  read_intensity(m, light, 2 * double(kPi) * (1 - (std::cos(inner) + std::cos(cone)) / 2));
}

void read_sun(const YamlMap &m, LightDesc &light) {
  m.check_keys({"type", "direction", "irradiance", "angular_diameter", "group"}, "a sun light");
  light.direction = read_direction(m.require("direction"));
  if (auto v = m.get("irradiance")) light.irradiance = v->rgb(kNonNegative);
  if (auto v = m.get("angular_diameter")) light.angular_diameter_degrees = v->real(Range::closed(0, 180));
}

LightDesc read_light(const YamlValue &value, const Shutter &shutter) {
  const YamlMap m = value.map();
  const YamlValue type = m.require("type");
  const std::string name = type.string();
  LightDesc light;
  light.where = value.location();
  if (name == "point") {
    light.type = LightType::Point;
    read_point(m, light);
  } else if (name == "spot") {
    light.type = LightType::Spot;
    read_spot(m, light);
  } else if (name == "sun") {
    light.type = LightType::Sun;
    read_sun(m, light);
  } else {
    type.fail("unknown light type '" + abbreviate(name) + "'; known: point, spot, sun");
  }
  if (auto v = m.get("group")) light.group = v->string();
  if (auto v = m.get("motion")) light.motion = read_rigid_motion(*v, shutter, "a light");
  return light;
}

}  // namespace

std::vector<LightDesc> read_lights(const YamlValue &section, const Shutter &shutter) {
  std::vector<LightDesc> out;
  if (section.is_null()) return out;
  for (const YamlValue &light : section.sequence()) out.push_back(read_light(light, shutter));
  return out;
}

}  // namespace nimbus::scene_yaml
