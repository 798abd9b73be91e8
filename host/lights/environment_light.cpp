// Environment: lat-long map (importance-sampled with a 2-D piecewise-constant distribution over
// luminance x sin(theta)) or a uniform colour. Directions use +z as up; u runs with the azimuth.
#include <nimbus/cpp/sampling.hpp>
#include "lights/light.hpp"

namespace nimbus {
namespace {

struct LatLong {
  float u, v, sin_theta;
};

LatLong to_latlong(const Vec3f &dir, float rotate) {
  float phi = atan2_fast(dir.y, dir.x) - rotate;
  phi -= 2 * kPi * std::floor(phi / (2 * kPi));
  // sin(theta) from x and y, not sqrt(1 - z^2): near the poles that difference cancels to a few bits,
  // and the solid-angle pdf divides by it. (No hypot: dir is a unit vector, x^2 + y^2 cannot overflow.)
  const float sin_theta = std::sqrt(dir.x * dir.x + dir.y * dir.y), theta = atan2_fast(sin_theta, dir.z);
  return {std::min(phi / (2 * kPi), 0x1.fffffep-1f), std::min(theta / kPi, 0x1.fffffep-1f), sin_theta};
}

size_t texel_of(const EnvironmentLight &env, const LatLong &ll) {
  const uint32_t x = std::min(uint32_t(ll.u * float(env.width)), env.width - 1);
  const uint32_t y = std::min(uint32_t(ll.v * float(env.height)), env.height - 1);
  return size_t(y) * env.width + x;
}

}  // namespace

double EnvironmentLight::finish_build() {
  texels.clear();
  if (map.empty()) return 4 * kPi * luminance(color);
  std::vector<float> weights(map.size());
  double integral = 0;
  const double texel_solid = (2 * kPi / width) * (kPi / height);
  for (uint32_t y = 0; y < height; ++y) {
    const float sin_theta = std::sin((float(y) + 0.5f) / float(height) * kPi);
    for (uint32_t x = 0; x < width; ++x) {
      const float lum = std::max(0.0f, luminance(map[size_t(y) * width + x]));
      weights[size_t(y) * width + x] = lum * sin_theta;
      integral += double(lum) * sin_theta * texel_solid;
    }
  }
  distribution = Distribution2D(weights, width, height);
  texels.resize(map.size());
  for (size_t i = 0; i < map.size(); ++i) texels[i] = {map[i], distribution.cell_pdf(i)};
  map = {};
  return integral;
}

Rgb EnvironmentLight::lookup(const Vec3f &dir) const {
  if (uniform()) return color;
  const LatLong ll = to_latlong(dir, rotate_radians);
  return bilinear ? interpolate(ll.u, ll.v) : texels[texel_of(*this, ll)].radiance;
}

Rgb EnvironmentLight::interpolate(float u, float v) const {
  // Between the four nearest texel centres: wrapping around in azimuth, clamped at the poles.
  const float fx = u * float(width) - 0.5f, fy = v * float(height) - 0.5f;
  const float x0f = std::floor(fx), y0f = std::floor(fy), tx = fx - x0f, ty = fy - y0f;
  const uint32_t x0 = (uint32_t(int32_t(x0f) + int32_t(width))) % width, x1 = (x0 + 1) % width;
  const uint32_t y0 = uint32_t(std::max(y0f, 0.0f)),
                 y1 = std::min(uint32_t(std::max(y0f + 1, 0.0f)), height - 1);
  const auto at = [&](uint32_t x, uint32_t y) { return texels[size_t(y) * width + x].radiance; };
  return (at(x0, y0) * (1 - tx) + at(x1, y0) * tx) * (1 - ty) +
         (at(x0, y1) * (1 - tx) + at(x1, y1) * tx) * ty;
}

float EnvironmentLight::pdf(const Vec3f &dir) const {
  if (uniform()) return kUniformSpherePdf;
  const LatLong ll = to_latlong(dir, rotate_radians);
  if (!(ll.sin_theta > 0)) return 0;
  return texels[texel_of(*this, ll)].pdf_uv / (2 * kPi * kPi * ll.sin_theta);
}

// Direction, solid-angle pdf and radiance for uniform numbers (u0, u1). The radiance comes from the
// sampled (u, v): no trip back through atan2, and the texel is the one whose density was drawn.
Vec3f environment_sample(const EnvironmentLight &env, float u0, float u1, float &pdf, Rgb &radiance) {
  if (env.uniform()) {
    pdf = kUniformSpherePdf;
    radiance = env.color;
    return sample_uniform_sphere(u0, u1);
  }
  float u, v;
  size_t cell = 0;
  env.distribution.sample(u0, u1, u, v, nullptr, &cell);
  const EnvironmentLight::Texel &texel = env.texels[cell];
  radiance = env.bilinear ? env.interpolate(u, v) : texel.radiance;
  const float theta = v * kPi, phi = u * 2 * kPi + env.rotate_radians;
  const float sin_theta = std::sin(theta);
  pdf = sin_theta > 0 ? texel.pdf_uv / (2 * kPi * kPi * sin_theta) : 0;
  return {sin_theta * std::cos(phi), sin_theta * std::sin(phi), std::cos(theta)};
}

}  // namespace nimbus
