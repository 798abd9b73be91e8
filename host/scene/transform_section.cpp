// `transform:` — {translate, rotate, scale} composed as translate * rotate * scale (scale first), or a
// full affine {matrix: [16 numbers, row-major]}.
#include <array>
#include <cmath>

#include "scene/sections.hpp"

namespace nimbus::scene_yaml {

namespace {

float nonzero_scale(const YamlValue &v) {
  const float s = v.real();
  if (s == 0) v.fail("must not be 0 (a zero scale flattens the object)");
  return s;
}

Vec3f read_scale(const YamlValue &v) {
  if (v.is_scalar()) return Vec3f(nonzero_scale(v));
  const std::vector<YamlValue> s = v.sequence_of(3, "a number or [sx, sy, sz]");
  return {nonzero_scale(s[0]), nonzero_scale(s[1]), nonzero_scale(s[2])};
}

Transform axis_angle(const YamlValue &v) {
  const std::vector<YamlValue> a = v.sequence_of(4, "[axis_x, axis_y, axis_z, degrees]");
  const Vec3f axis{a[0].real(), a[1].real(), a[2].real()};
  if (!(length(axis) > 0)) v.fail("rotation axis must not be the zero vector");
  return Transform::rotate(a[3].real(), axis);
}

// Two spellings: [rx, ry, rz] in degrees about x, then y, then z; or a list of [axis..., degrees]
// rotations applied in the order written. A lone [ax, ay, az, deg] is read as a one-element list.
Transform read_rotation(const YamlValue &v) {
  const std::vector<YamlValue> items = v.sequence();
  const char *forms =
      "[rx, ry, rz] (degrees about x, then y, then z) or a list of [axis_x, axis_y, axis_z, degrees]";
  if (items.empty()) v.fail(std::string("expected ") + forms + ", got an empty sequence");
  if (items.front().is_sequence()) {
    Transform r;
    for (const YamlValue &item : items) r = axis_angle(item) * r;
    return r;
  }
  if (items.size() == 4) return axis_angle(v);
  if (items.size() != 3)
    v.fail(std::string("expected ") + forms + ", got " + std::to_string(items.size()) + " numbers");
  const float rx = items[0].real(), ry = items[1].real(), rz = items[2].real();
  return Transform::rotate(rz, {0, 0, 1}) * Transform::rotate(ry, {0, 1, 0}) *
         Transform::rotate(rx, {1, 0, 0});
}

Transform read_matrix(const YamlValue &v) {
  std::vector<YamlValue> numbers;
  const std::vector<YamlValue> items = v.sequence();
  if (items.size() == 4 && items.front().is_sequence()) {  // also accept four rows of four
    for (const YamlValue &row : items)
      for (YamlValue &x : row.sequence_of(4, "a row of 4 numbers")) numbers.push_back(std::move(x));
  } else {
    numbers = v.sequence_of(16, "16 numbers, row-major");
  }
  std::array<float, 16> m{};
  for (size_t i = 0; i < 16; ++i) m[i] = numbers[i].real();
  // Projective matrices do not map spheres to spheres or planes to planes the way the shapes assume.
  if (m[12] != 0 || m[13] != 0 || m[14] != 0 || m[15] != 1)
    v.fail("the last row must be [0, 0, 0, 1] (affine transforms only)");
  return Transform(m);
}

}  // namespace

Transform read_transform(const YamlValue &value) {
  return read_transform(value.map({"translate", "rotate", "scale", "matrix"}));
}

Transform read_transform(const YamlMap &m) {
  if (auto matrix = m.get("matrix")) {
    for (const char *other : {"translate", "rotate", "scale"})
      if (m.has(other)) m.key(other).fail("cannot be combined with 'matrix'");
    const Transform t = read_matrix(*matrix);
    if (!(std::abs(t.determinant3()) > 0)) matrix->fail("the matrix is singular");
    return t;
  }
  Transform s, r, t;
  if (auto v = m.get("scale")) s = Transform::scale(read_scale(*v));
  if (auto v = m.get("rotate")) r = read_rotation(*v);
  if (auto v = m.get("translate")) t = Transform::translate(v->vec3());
  return t * r * s;
}

}  // namespace nimbus::scene_yaml
