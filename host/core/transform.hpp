// Affine transforms as 4x4 row-major matrices acting on column vectors (pbrt-v4 convention).
#pragma once

#include <array>

#include <nimbus/cpp/math.hpp>

namespace nimbus {

class Transform {
 public:
  Transform() = default;
  explicit Transform(const std::array<float, 16> &m) : m_(m) {}

  static Transform translate(const Vec3f &t) {
    return Transform({1, 0, 0, t.x, 0, 1, 0, t.y, 0, 0, 1, t.z, 0, 0, 0, 1});
  }
  static Transform scale(const Vec3f &s) {
    return Transform({s.x, 0, 0, 0, 0, s.y, 0, 0, 0, 0, s.z, 0, 0, 0, 0, 1});
  }
  // Rotation by `degrees` about a unit axis (right-handed).
  static Transform rotate(float degrees, const Vec3f &axis) {
    const Vec3f a = normalize(axis);
    const float s = std::sin(radians(degrees)), c = std::cos(radians(degrees)), t = 1 - c;
    return Transform({a.x * a.x * t + c, a.x * a.y * t - a.z * s, a.x * a.z * t + a.y * s, 0,
                      a.x * a.y * t + a.z * s, a.y * a.y * t + c, a.y * a.z * t - a.x * s, 0,
                      a.x * a.z * t - a.y * s, a.y * a.z * t + a.x * s, a.z * a.z * t + c, 0, 0, 0, 0, 1});
  }

  float operator()(int r, int c) const { return m_[r * 4 + c]; }
  const std::array<float, 16> &matrix() const { return m_; }

  Transform operator*(const Transform &o) const {
    std::array<float, 16> r{};
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) {
        double s = 0;
        for (int k = 0; k < 4; ++k) s += double(m_[i * 4 + k]) * o.m_[k * 4 + j];
        r[i * 4 + j] = float(s);
      }
    return Transform(r);
  }

  Vec3f point(const Vec3f &p) const {
    return {m_[0] * p.x + m_[1] * p.y + m_[2] * p.z + m_[3], m_[4] * p.x + m_[5] * p.y + m_[6] * p.z + m_[7],
            m_[8] * p.x + m_[9] * p.y + m_[10] * p.z + m_[11]};
  }
  Vec3f vector(const Vec3f &v) const {
    return {m_[0] * v.x + m_[1] * v.y + m_[2] * v.z, m_[4] * v.x + m_[5] * v.y + m_[6] * v.z,
            m_[8] * v.x + m_[9] * v.y + m_[10] * v.z};
  }
  // Normals transform with the inverse transpose of the linear part; the result is not normalised.
  Vec3f normal(const Vec3f &n) const {
    const Vec3f c0{m_[0], m_[4], m_[8]}, c1{m_[1], m_[5], m_[9]}, c2{m_[2], m_[6], m_[10]};
    // Cofactor matrix rows equal the inverse transpose up to the (positive or negative) determinant.
    const Vec3f r0 = cross(c1, c2), r1 = cross(c2, c0), r2 = cross(c0, c1);
    const Vec3f out = r0 * n.x + r1 * n.y + r2 * n.z;
    return determinant3() < 0 ? -out : out;
  }
  float determinant3() const {
    return m_[0] * (m_[5] * m_[10] - m_[6] * m_[9]) - m_[1] * (m_[4] * m_[10] - m_[6] * m_[8]) +
           m_[2] * (m_[4] * m_[9] - m_[5] * m_[8]);
  }
  // The inverse affine transform (the linear part by cofactors over the determinant); the transform must
  // not be singular.
  Transform inverse() const {
    const double det = determinant3();
    std::array<float, 16> r{0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1};
    const auto at = [&](int i, int j) { return double(m_[size_t(i * 4 + j)]); };
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {  // inverse(i, j) = cofactor(j, i) / det
        const int a0 = (j + 1) % 3, a1 = (j + 2) % 3, b0 = (i + 1) % 3, b1 = (i + 2) % 3;
        r[size_t(i * 4 + j)] = float((at(a0, b0) * at(a1, b1) - at(a0, b1) * at(a1, b0)) / det);
      }
    for (int i = 0; i < 3; ++i)
      r[size_t(i * 4 + 3)] =
          -(r[size_t(i * 4)] * m_[3] + r[size_t(i * 4 + 1)] * m_[7] + r[size_t(i * 4 + 2)] * m_[11]);
    return Transform(r);
  }
  // Scale factors along x, y, z of the linear part (lengths of its columns).
  Vec3f axis_scales() const {
    return {length(Vec3f{m_[0], m_[4], m_[8]}), length(Vec3f{m_[1], m_[5], m_[9]}),
            length(Vec3f{m_[2], m_[6], m_[10]})};
  }

 private:
  std::array<float, 16> m_{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
};

}  // namespace nimbus
