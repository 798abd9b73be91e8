// `camera:` — a perspective camera with an optional thin lens.
#include <cmath>

#include "scene/sections.hpp"

namespace nimbus::scene_yaml {

CameraDesc read_camera(const YamlValue &section) {
  CameraDesc c;
  if (section.is_null()) return c;  // `camera:` with nothing under it: all defaults
  const YamlMap m = section.map(
      {"type", "position", "look_at", "up", "fov", "aperture", "focus_distance", "shutter", "motion"});

  if (auto v = m.get("type")) {
    const std::string type = v->string();
    if (type != "perspective")
      v->fail("unknown camera type '" + abbreviate(type) + "'; supported: perspective");
  }
  if (auto v = m.get("position")) c.position = v->vec3();
  if (auto v = m.get("look_at")) c.look_at = v->vec3();
  if (auto v = m.get("up")) c.up = v->vec3();
  if (auto v = m.get("fov")) c.fov_degrees = v->real(Range::open(0, 180));
  if (auto v = m.get("aperture")) c.aperture = v->real(Range::at_least(0));
  if (auto v = m.get("focus_distance")) c.focus_distance = v->real(Range::greater_than(0));
  if (auto v = m.get("shutter")) c.shutter = read_shutter(*v);
  if (auto v = m.get("motion")) c.motion = read_rigid_motion(*v, c.shutter, "the camera");

  // The camera frame is built from (look_at - position) and up; reject inputs that leave it undefined.
  // Errors point at the key that was written, or at the section when both came from defaults.
  const auto at = [&](std::string_view key) { return m.get(key).value_or(section); };
  const Vec3f view = c.look_at - c.position;
  const float view_len = length(view);
  if (!(view_len > 0)) {
    at(m.has("look_at") ? "look_at" : "position")
        .fail("look_at equals position; the camera has no viewing direction");
  }
  const float up_len = length(c.up);
  if (!(up_len > 0)) at("up").fail("up must not be the zero vector");
  const float sin_angle = length(cross(view / view_len, c.up / up_len));
  if (!(sin_angle > 1e-4f)) at("up").fail("up is parallel to the viewing direction (look_at - position)");
  return c;
}

}  // namespace nimbus::scene_yaml
