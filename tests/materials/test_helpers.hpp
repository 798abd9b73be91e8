// Shared by the material tests: a seeded RNG, direction helpers and the catalogue of BSDFs under test.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nimbus/cpp/math.hpp>
#include "materials/bsdf.hpp"

namespace nimbus::test {

// PCG32 (O'Neill 2014): tests must not depend on the standard library's engine or distributions, whose
// output differs between implementations.
class Pcg32 {
 public:
  explicit Pcg32(uint64_t seed, uint64_t stream = 1) : inc_((stream << 1u) | 1u) {
    next();
    state_ += seed;
    next();
  }
  uint32_t next() {
    const uint64_t old = state_;
    state_ = old * 6364136223846793005ull + inc_;
    const uint32_t xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
    const uint32_t rot = static_cast<uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((~rot + 1u) & 31u));
  }
  // Uniform in [0, 1).
  float uniform() { return static_cast<float>(next() >> 8) * 0x1p-24f; }
  Vec2f uniform2() {
    const float a = uniform();
    return {a, uniform()};
  }

 private:
  uint64_t state_ = 0, inc_;
};

// Unit direction at polar angle theta from +z (degrees; > 90 is below the surface) and azimuth phi.
Vec3f direction_deg(float theta_deg, float phi_deg = 30);

inline Vec3f mirror_z(const Vec3f &w) { return {-w.x, -w.y, w.z}; }

// A BSDF with a readable name for test output.
struct NamedBsdf {
  std::string name;
  Bsdf bsdf;
  bool delta = false;
  float ior = 0;  // dielectrics only: the relative IOR crossed when entering
};

NamedBsdf diffuse_case(Rgb albedo);
NamedBsdf conductor_case(float alpha);  // gold
NamedBsdf mirror_case(float alpha, float reflectance = 1);
NamedBsdf dielectric_case(float ior, float alpha);

// Every material family at the parameter extremes the renderer may meet, rough and smooth.
std::vector<NamedBsdf> extreme_catalogue();

// FNV-1a: a seed from a test's name that, unlike std::hash, is the same on every standard library.
inline uint64_t seed_from(const std::string &name) {
  uint64_t h = 14695981039346656037ull;
  for (unsigned char c : name) h = (h ^ c) * 1099511628211ull;
  return h;
}

// gtest parameter names: letters, digits and underscores only.
std::string sanitize_name(std::string name);

}  // namespace nimbus::test
