// Three-float vectors held in one four-wide register (GCC and Clang vector extensions; the fourth lane
// is carried along and never read). A lane-wise operation is one instruction where Vec3f's scalar code
// takes three, and a vector takes one register instead of three, yet every lane rounds exactly as Vec3f
// does and dot products add in Vec3f's order: code moved from Vec3f to Lanes3 gives the same bits.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include <nimbus/cpp/math.hpp>

namespace nimbus {

struct Lanes3 {
  using Floats = float __attribute__((vector_size(16)));
  using Ints = int32_t __attribute__((vector_size(16)));
  Floats v;

  // Reads exactly three floats: the vector may end an array, and a wider load of floats just written
  // one by one would wait for them to reach the cache.
  static Lanes3 load(const float *p) { return {Floats{p[0], p[1], p[2], 0.0f}}; }
  // The same with one 8-byte and one 4-byte load, for memory not written just before (mesh data): an
  // 8-byte load of two floats each just stored on its own waits for them to reach the cache.
  static Lanes3 load_settled(const float *p) {
    double xy;
    std::memcpy(&xy, p, sizeof xy);
    using Doubles = double __attribute__((vector_size(16)));
    const Floats lo = reinterpret_cast<Floats>(Doubles{xy, 0.0}), hi{p[2], 0.0f, 0.0f, 0.0f};
    return {__builtin_shufflevector(lo, hi, 0, 1, 4, 5)};
  }
  static Lanes3 of(const Vec3f &a) { return {Floats{a.x, a.y, a.z, 0.0f}}; }
  Vec3f vec3() const { return {v[0], v[1], v[2]}; }
  float x() const { return v[0]; }
  float y() const { return v[1]; }
  float z() const { return v[2]; }
};

inline Lanes3 operator+(const Lanes3 &a, const Lanes3 &b) { return {a.v + b.v}; }
inline Lanes3 operator-(const Lanes3 &a, const Lanes3 &b) { return {a.v - b.v}; }
inline Lanes3 operator*(const Lanes3 &a, const Lanes3 &b) { return {a.v * b.v}; }
inline Lanes3 operator*(const Lanes3 &a, float s) { return {a.v * s}; }
inline Lanes3 operator-(const Lanes3 &a) { return {-a.v}; }
inline Lanes3 abs(const Lanes3 &a) {
  return {reinterpret_cast<Lanes3::Floats>(reinterpret_cast<Lanes3::Ints>(a.v) & 0x7fffffff)};
}
// Vec3f's (x * x' + y * y') + z * z'.
inline float dot(const Lanes3 &a, const Lanes3 &b) {
  const Lanes3::Floats m = a.v * b.v;
  return m[0] + m[1] + m[2];
}
inline float length(const Lanes3 &a) { return std::sqrt(dot(a, a)); }
// Vec3f's normalize: a times the reciprocal of its length.
inline Lanes3 normalize(const Lanes3 &a) { return a * (1.0f / length(a)); }
inline float max_component(const Lanes3 &a) { return std::max(a.x(), std::max(a.y(), a.z())); }
inline Lanes3 cross(const Lanes3 &a, const Lanes3 &b) {
  const Lanes3::Floats a1 = __builtin_shufflevector(a.v, a.v, 1, 2, 0, 3);
  const Lanes3::Floats b1 = __builtin_shufflevector(b.v, b.v, 2, 0, 1, 3);
  const Lanes3::Floats a2 = __builtin_shufflevector(a.v, a.v, 2, 0, 1, 3);
  const Lanes3::Floats b2 = __builtin_shufflevector(b.v, b.v, 1, 2, 0, 3);
  return {a1 * b1 - a2 * b2};
}

// Four floats stored with one 16-byte store at dst.
inline void store4(void *dst, const Lanes3::Floats &f) { std::memcpy(dst, &f, sizeof f); }

}  // namespace nimbus
