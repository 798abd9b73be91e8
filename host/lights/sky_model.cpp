#include "lights/sky_model.hpp"

namespace nimbus {
namespace {

struct Perez {
  float A, B, C, D, E;
  float operator()(float cos_theta, float gamma) const {
    const float cg = std::cos(gamma);
    return (1 + A * std::exp(B / std::max(cos_theta, 1e-3f))) * (1 + C * std::exp(D * gamma) + E * cg * cg);
  }
};

struct Sky {
  Perez Y, x, y;
  float Yz, xz, yz, theta_s;

  Sky(const Vec3f &to_sun, float T) {
    theta_s = std::acos(clamp(to_sun.z, -1, 1));
    theta_s = std::min(theta_s, radians(89.9f));  // the model is defined for a sun above the horizon
    const float t = theta_s, t2 = t * t, t3 = t2 * t;
    const float chi = (4.0f / 9.0f - T / 120.0f) * (kPi - 2 * t);
    Yz = (4.0453f * T - 4.9710f) * std::tan(chi) - 0.2155f * T + 2.4192f;  // kcd/m^2
    xz = T * T * (0.00166f * t3 - 0.00375f * t2 + 0.00209f * t) +
         T * (-0.02903f * t3 + 0.06377f * t2 - 0.03202f * t + 0.00394f) +
         (0.11693f * t3 - 0.21196f * t2 + 0.06052f * t + 0.25886f);
    yz = T * T * (0.00275f * t3 - 0.00610f * t2 + 0.00317f * t) +
         T * (-0.04214f * t3 + 0.08970f * t2 - 0.04153f * t + 0.00516f) +
         (0.15346f * t3 - 0.26756f * t2 + 0.06670f * t + 0.26688f);
    Y = {0.1787f * T - 1.4630f, -0.3554f * T + 0.4275f, -0.0227f * T + 5.3251f, 0.1206f * T - 2.5771f,
         -0.0670f * T + 0.3703f};
    x = {-0.0193f * T - 0.2592f, -0.0665f * T + 0.0008f, -0.0004f * T + 0.2125f, -0.0641f * T - 0.8989f,
         -0.0033f * T + 0.0452f};
    y = {-0.0167f * T - 0.2608f, -0.0950f * T + 0.0092f, -0.0079f * T + 0.2102f, -0.0441f * T - 1.6537f,
         -0.0109f * T + 0.0529f};
  }

  Rgb radiance(float cos_theta, float gamma) const {
    const float lum = std::max(0.0f, Yz * Y(cos_theta, gamma) / Y(1, theta_s)) * 1000.0f;  // cd/m^2
    const float cx = xz * x(cos_theta, gamma) / x(1, theta_s);
    const float cy = yz * y(cos_theta, gamma) / y(1, theta_s);
    if (!(cy > 1e-4f)) return Rgb(0);
    const float X = cx * lum / cy, Z = (1 - cx - cy) * lum / cy;
    const Rgb rgb{3.2406f * X - 1.5372f * lum - 0.4986f * Z, -0.9689f * X + 1.8758f * lum + 0.0415f * Z,
                  0.0557f * X - 0.2040f * lum + 1.0570f * Z};
    return max(rgb, Rgb(0)) / 683.0f;
  }
};

}  // namespace

Rgb preetham_sky_radiance(const Vec3f &dir, const Vec3f &to_sun, float turbidity) {
  const Sky sky(to_sun, turbidity);
  const Vec3f sun{to_sun.x, to_sun.y, std::max(to_sun.z, std::cos(sky.theta_s))};
  if (dir.z >= 0.01f) return sky.radiance(dir.z, std::acos(clamp(dot(dir, normalize(sun)), -1, 1)));
  const Vec3f horizon = normalize(Vec3f{dir.x, dir.y, 0.01f});
  return sky.radiance(horizon.z, std::acos(clamp(dot(horizon, normalize(sun)), -1, 1))) * 0.25f;
}

std::vector<Rgb> bake_sky(const Vec3f &to_sun, float turbidity, uint32_t width, uint32_t height) {
  std::vector<Rgb> map(size_t(width) * height);
  for (uint32_t yy = 0; yy < height; ++yy)
    for (uint32_t xx = 0; xx < width; ++xx) {
      const float theta = (float(yy) + 0.5f) / float(height) * kPi;
      const float phi = (float(xx) + 0.5f) / float(width) * 2 * kPi;
      const Vec3f d{std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
      map[size_t(yy) * width + xx] = preetham_sky_radiance(d, to_sun, turbidity);
    }
  return map;
}

}  // namespace nimbus
