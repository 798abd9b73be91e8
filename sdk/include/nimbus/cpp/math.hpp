// Small value types for geometry and colour. No I/O, no allocation.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>

namespace nimbus {

inline constexpr float kPi = std::numbers::pi_v<float>;
inline constexpr float kInvPi = std::numbers::inv_pi_v<float>;
inline constexpr float kInfinity = std::numeric_limits<float>::infinity();

struct Vec3f {
  float x = 0, y = 0, z = 0;

  constexpr Vec3f() = default;
  constexpr Vec3f(float x_, float y_, float z_) : x(x_), y(y_), z(z_) {}
  constexpr explicit Vec3f(float s) : x(s), y(s), z(s) {}
  static constexpr Vec3f load(const float *p) { return {p[0], p[1], p[2]}; }
  constexpr void store(float *p) const { p[0] = x, p[1] = y, p[2] = z; }

  constexpr float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr float &operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr Vec3f operator-() const { return {-x, -y, -z}; }
  constexpr Vec3f &operator+=(const Vec3f &o) { return x += o.x, y += o.y, z += o.z, *this; }
  constexpr Vec3f &operator-=(const Vec3f &o) { return x -= o.x, y -= o.y, z -= o.z, *this; }
  constexpr Vec3f &operator*=(const Vec3f &o) { return x *= o.x, y *= o.y, z *= o.z, *this; }
  constexpr Vec3f &operator*=(float s) { return x *= s, y *= s, z *= s, *this; }
  constexpr Vec3f &operator/=(float s) { return *this *= 1.0f / s; }
  constexpr bool operator==(const Vec3f &) const = default;
};

constexpr Vec3f operator+(Vec3f a, const Vec3f &b) { return a += b; }
constexpr Vec3f operator-(Vec3f a, const Vec3f &b) { return a -= b; }
constexpr Vec3f operator*(Vec3f a, const Vec3f &b) { return a *= b; }
constexpr Vec3f operator*(Vec3f a, float s) { return a *= s; }
constexpr Vec3f operator*(float s, Vec3f a) { return a *= s; }
constexpr Vec3f operator/(Vec3f a, float s) { return a /= s; }
constexpr Vec3f operator/(const Vec3f &a, const Vec3f &b) { return {a.x / b.x, a.y / b.y, a.z / b.z}; }

constexpr float dot(const Vec3f &a, const Vec3f &b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr Vec3f cross(const Vec3f &a, const Vec3f &b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline float length(const Vec3f &a) { return std::sqrt(dot(a, a)); }
constexpr float length_squared(const Vec3f &a) { return dot(a, a); }
inline Vec3f normalize(const Vec3f &a) { return a / length(a); }
inline Vec3f abs(const Vec3f &a) { return {std::abs(a.x), std::abs(a.y), std::abs(a.z)}; }
constexpr Vec3f min(const Vec3f &a, const Vec3f &b) {
  return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)};
}
constexpr Vec3f max(const Vec3f &a, const Vec3f &b) {
  return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)};
}
constexpr float max_component(const Vec3f &a) { return std::max(a.x, std::max(a.y, a.z)); }
// How far to move a point off the surface it was computed on when no tighter error bound is at hand
// (emission points in plugins): 2^-19 of its largest coordinate, a few times the rounding error of a point
// interpolated on a triangle, so it scales with the scene from 1e-4 to 1e6 units.
inline float relative_offset(const Vec3f &p) { return std::max(max_component(abs(p)), 0x1p-100f) * 0x1p-19f; }
constexpr bool is_black(const Vec3f &a) { return a.x == 0 && a.y == 0 && a.z == 0; }
inline bool is_finite(const Vec3f &a) {
  return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}
// Rec. 709 luminance of linear RGB.
constexpr float luminance(const Vec3f &c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }
inline Vec3f exp(const Vec3f &a) { return {std::exp(a.x), std::exp(a.y), std::exp(a.z)}; }
inline Vec3f sqrt(const Vec3f &a) { return {std::sqrt(a.x), std::sqrt(a.y), std::sqrt(a.z)}; }

// Linear RGB radiance, reflectance or weight.
using Rgb = Vec3f;

struct Vec2f {
  float x = 0, y = 0;
};

// Orthonormal basis around a unit normal; local z is the normal.
struct Frame {
  Vec3f s, t, n;

  // Duff et al. 2017, "Building an Orthonormal Basis, Revisited": branchless and continuous.
  static Frame from_normal(const Vec3f &n) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    return {{1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x}, {b, sign + n.y * n.y * a, -n.y}, n};
  }
  // Basis whose s axis follows the tangent `dpdu` projected onto the plane of n (falls back to any basis).
  static Frame from_normal_tangent(const Vec3f &n, const Vec3f &dpdu) {
    const Vec3f s = dpdu - n * dot(n, dpdu);
    const float len2 = length_squared(s);
    if (!(len2 > 1e-12f)) return from_normal(n);
    const Vec3f su = s / std::sqrt(len2);
    return {su, cross(n, su), n};
  }
  Vec3f to_local(const Vec3f &v) const { return {dot(v, s), dot(v, t), dot(v, n)}; }
  Vec3f to_world(const Vec3f &v) const { return s * v.x + t * v.y + n * v.z; }
};

// The next float towards +infinity (up) or -infinity: std::nextafter(v, +-inf) for every finite v, as a
// step of the bit pattern (pbrt-v4's NextFloatUp / NextFloatDown), decided on the bits alone so that a
// denormals-are-zero mode cannot change it. std::nextafter is a libm call, and every spawned ray needs
// three steps: inline bit steps keep calls off that hot path.
constexpr float next_float(float v, bool up) {
  const uint32_t bits = std::bit_cast<uint32_t>(v);
  if ((bits & 0x7f800000u) == 0x7f800000u) return v;                  // infinite or NaN
  if ((bits & 0x7fffffffu) == 0) return up ? 0x1p-149f : -0x1p-149f;  // either zero: the smallest subnormal
  return std::bit_cast<float>((bits >> 31 == 0) == up ? bits + 1 : bits - 1);  // away from / towards zero
}

constexpr float sqr(float x) { return x * x; }
constexpr float clamp(float x, float lo, float hi) { return std::min(hi, std::max(lo, x)); }
inline float safe_sqrt(float x) { return std::sqrt(std::max(0.0f, x)); }
constexpr float radians(float degrees) { return degrees * (kPi / 180.0f); }

// atan2 in float with Cephes' atanf reduction and polynomial (within 4e-7 rad, two float ulps of pi; tested):
// a third of libm's cost, and environment lookups do two per escaped ray.
inline float atan2_fast(float y, float x) {
  const float ax = std::abs(x), ay = std::abs(y);
  if (!(ax > 0) && !(ay > 0)) return std::atan2(y, x);  // zeros (signed) and NaN as libm has them
  // atan(t), t = min/max in [0, 1], reduced around tan(pi/8).
  const bool swap = ay > ax;
  float t = swap ? ax / ay : ay / ax, base = 0;
  if (t > 0.41421356f) base = kPi / 4, t = (t - 1) / (t + 1);
  const float z = t * t;
  float a = base +
            ((((8.05374449538e-2f * z - 1.38776856032e-1f) * z + 1.99777106478e-1f) * z - 3.33329491539e-1f) *
                 z * t +
             t);
  if (swap) a = kPi / 2 - a;
  if (x < 0) a = kPi - a;
  return std::signbit(y) ? -a : a;
}

}  // namespace nimbus
