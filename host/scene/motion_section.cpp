// `camera.shutter:` and an object's `motion:` — the time over which the film is exposed, and transforms
// keyed in time within it (core/shutter.hpp, core/motion_transform.hpp).
#include <algorithm>
#include <cmath>
#include <string>

#include "scene/sections.hpp"

namespace nimbus::scene_yaml {

Shutter read_shutter(const YamlValue &value) {
  const YamlMap m = value.map({"open", "close", "curve"});
  const float open = m.has("open") ? m.get("open")->real() : 0.0f;
  const YamlValue close_value = m.require("close");
  const float close = close_value.real();
  if (!(close >= open))
    close_value.fail("the shutter closes (" + format_number(close) + ") before it opens (" +
                     format_number(open) + ")");
  std::vector<std::array<float, 2>> curve;
  if (auto v = m.get("curve")) {
    // Knots [x, exposure] over the shutter normalised to [0, 1]: x from 0 to 1, never decreasing.
    double area = 0;
    for (const YamlValue &knot : v->sequence()) {
      const std::vector<YamlValue> k = knot.sequence_of(2, "[x, exposure] with x in [0, 1]");
      const float x = k[0].real(Range::closed(0, 1)), y = k[1].real(Range::at_least(0));
      if (curve.empty() && x != 0) k[0].fail("the curve must start at x = 0");
      if (!curve.empty() && x < curve.back()[0]) k[0].fail("curve knots must not go back in x");
      if (!curve.empty()) area += 0.5 * (double(y) + curve.back()[1]) * (double(x) - curve.back()[0]);
      curve.push_back({x, y});
    }
    if (curve.size() < 2 || curve.back()[0] != 1) v->fail("the curve must run from x = 0 to x = 1");
    if (!(area > 0)) v->fail("the curve exposes nothing (its area is 0)");
  }
  return Shutter(open, close, std::move(curve));
}

std::vector<MotionTransform::Key> read_motion(
    const YamlValue &value, const Shutter &shutter,
    const std::function<void(const Transform &, const YamlValue &)> &check) {
  const std::vector<YamlValue> items = value.sequence();
  if (items.empty()) value.fail("expected at least one key {time, translate, rotate, scale}");
  std::vector<MotionTransform::Key> keys;
  std::string previous;  // the previous key's time as written
  for (const YamlValue &item : items) {
    const YamlMap key = item.map({"time", "translate", "rotate", "scale", "matrix"});
    const YamlValue time_value = key.require("time");
    const float time = time_value.real();
    if (items.size() > 1 && !(time >= shutter.open() && time <= shutter.close()))
      time_value.fail("time " + time_value.shown() + " lies outside the shutter [" +
                      format_number(shutter.open()) + ", " + format_number(shutter.close()) +
                      "] (camera.shutter)");
    if (!keys.empty() && !(time > keys.back().time))
      time_value.fail("keys out of order: time " + time_value.shown() + " follows " + previous);
    previous = time_value.shown();
    const Transform t = read_transform(key);
    check(t, item);
    if (!keys.empty()) {
      // Embree turns between time steps along the shorter arc; half a turn between two keys is ambiguous.
      const float c =
          std::abs(Decomposed::of(keys.back().transform).rotation.dot(Decomposed::of(t).rotation));
      if (c < 1e-3f)
        item.fail(
            "the rotation turns half a turn (180 degrees) since the previous key, which has no one way "
            "to turn: add a key between them");
    }
    keys.push_back({time, t});
  }
  return keys;
}

std::shared_ptr<const MotionTransform> read_rigid_motion(const YamlValue &value, const Shutter &shutter,
                                                         std::string_view what) {
  const auto keys = read_motion(value, shutter, [&](const Transform &t, const YamlValue &at) {
    const auto &s = Decomposed::of(t).scale_skew;
    const float off = std::max({std::abs(s[0] - 1), std::abs(s[1] - 1), std::abs(s[2] - 1), std::abs(s[3]),
                                std::abs(s[4]), std::abs(s[5])});
    if (off > 1e-4f) at.fail(std::string(what) + " moves rigidly: translate and rotate only (no scale)");
  });
  return std::make_shared<const MotionTransform>(keys, shutter.open(), shutter.close());
}

void read_deformation(const YamlValue &value, MeshData &mesh, MeshLibrary &library, const Shutter &shutter) {
  const std::vector<YamlValue> items = value.sequence();
  if (items.size() < 2)
    value.fail("expected at least two shapes of the mesh, evenly spaced over the shutter");
  if (shutter.instantaneous())
    value.fail(
        "the shapes are spread over camera.shutter, which opens and closes at once: give it a close time");
  bool normals = !mesh.normals.empty();
  std::vector<std::vector<Vec3f>> positions, normal_steps;
  for (const YamlValue &item : items) {
    std::vector<Vec3f> p, n;
    if (item.is_scalar()) {  // a file of the same mesh in another shape
      const std::shared_ptr<const LoadedMesh> loaded = library.load(item);
      if (loaded->mesh.indices != mesh.indices)
        item.fail("its triangles are not the mesh's (" + std::to_string(loaded->mesh.indices.size() / 3) +
                  " triangles against " + std::to_string(mesh.indices.size() / 3) + ", or other vertices)");
      p = loaded->mesh.positions, n = loaded->mesh.normals;
    } else {
      for (const YamlValue &v : item.sequence()) p.push_back(v.vec3());
    }
    if (p.size() != mesh.positions.size())
      item.fail("has " + std::to_string(p.size()) + " vertices but the mesh has " +
                std::to_string(mesh.positions.size()));
    normals = normals && n.size() == p.size();
    positions.push_back(std::move(p)), normal_steps.push_back(std::move(n));
  }
  mesh.positions = positions.front();
  mesh.position_steps = std::move(positions);
  // Normals follow the shape only when every step has them; otherwise the mesh shades flat.
  if (normals) {
    mesh.normals = normal_steps.front();
    mesh.normal_steps = std::move(normal_steps);
  } else {
    mesh.normals.clear();
  }
  mesh.steps_open = shutter.open(), mesh.steps_close = shutter.close();
}

}  // namespace nimbus::scene_yaml
