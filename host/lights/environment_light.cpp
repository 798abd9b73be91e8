// Environment: lat-long map (importance-sampled with a 2-D piecewise-constant distribution over
// luminance x sin(theta)) or a uniform colour. Directions use +z as up; u runs with the azimuth.
#include "core/sampling.hpp"
#include "lights/light.hpp"

namespace nimbus {
namespace {

struct LatLong {
  float u, v, sin_theta;
};

LatLong to_latlong(const Vec3f &dir, float rotate) {
  float phi = std::atan2(dir.y, dir.x) - rotate;
  phi -= 2 * kPi * std::floor(phi / (2 * kPi));
  // sin(theta) from x and y, not sqrt(1 - z^2): near the poles that difference cancels to a few bits,
  // and the solid-angle pdf divides by it.
  const float sin_theta = std::hypot(dir.x, dir.y), theta = std::atan2(sin_theta, dir.z);
  return {std::min(phi / (2 * kPi), 0x1.fffffep-1f), std::min(theta / kPi, 0x1.fffffep-1f), sin_theta};
}

}  // namespace

Rgb EnvironmentLight::lookup(const Vec3f &dir) const {
  if (map.empty()) return color;
  const LatLong ll = to_latlong(dir, rotate_radians);
  const uint32_t x = std::min(uint32_t(ll.u * float(width)), width - 1);
  const uint32_t y = std::min(uint32_t(ll.v * float(height)), height - 1);
  return map[size_t(y) * width + x];
}

float EnvironmentLight::pdf(const Vec3f &dir) const {
  if (map.empty()) return kUniformSpherePdf;
  const LatLong ll = to_latlong(dir, rotate_radians);
  if (!(ll.sin_theta > 0)) return 0;
  return distribution.pdf(ll.u, ll.v) / (2 * kPi * kPi * ll.sin_theta);
}

// Direction and solid-angle pdf for uniform numbers (u0, u1).
Vec3f environment_sample(const EnvironmentLight &env, float u0, float u1, float &pdf) {
  if (env.map.empty()) {
    pdf = kUniformSpherePdf;
    return sample_uniform_sphere(u0, u1);
  }
  float u, v, pdf_uv;
  env.distribution.sample(u0, u1, u, v, &pdf_uv);
  const float theta = v * kPi, phi = u * 2 * kPi + env.rotate_radians;
  const float sin_theta = std::sin(theta);
  pdf = sin_theta > 0 ? pdf_uv / (2 * kPi * kPi * sin_theta) : 0;
  return {sin_theta * std::cos(phi), sin_theta * std::sin(phi), std::cos(theta)};
}

}  // namespace nimbus
