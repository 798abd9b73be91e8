#include "test_helpers.hpp"

#include <cstdio>

#include "scene/metals.hpp"

namespace nimbus::test {

Vec3f direction_deg(float theta_deg, float phi_deg) {
  const double t = theta_deg * 3.14159265358979323846 / 180, p = phi_deg * 3.14159265358979323846 / 180;
  return Vec3f(static_cast<float>(std::sin(t) * std::cos(p)), static_cast<float>(std::sin(t) * std::sin(p)),
               static_cast<float>(std::cos(t)));
}

static std::string fmt(const char *f, double a, double b = 0) {
  char buf[96];
  std::snprintf(buf, sizeof buf, f, a, b);
  return buf;
}

NamedBsdf diffuse_case(Rgb albedo) { return {fmt("diffuse_%g", albedo.x), DiffuseBsdf(albedo), false}; }

NamedBsdf conductor_case(float alpha) {
  const MetalIor gold = *find_metal("gold");
  const ConductorBsdf c = ConductorBsdf::fresnel(gold.eta, gold.k, alpha);
  return {fmt("gold_a%g", alpha), c, c.min_alpha() == 0};
}

NamedBsdf mirror_case(float alpha, float reflectance) {
  const ConductorBsdf c = ConductorBsdf::mirror(Rgb(reflectance), alpha);
  return {fmt("mirror_a%g_r%g", alpha, reflectance), c, c.min_alpha() == 0};
}

NamedBsdf dielectric_case(float ior, float alpha) {
  const DielectricBsdf d(ior, alpha);
  return {fmt("glass_ior%g_a%g", ior, alpha), d, d.min_alpha() == 0, d.eta()};
}

std::vector<NamedBsdf> extreme_catalogue() {
  std::vector<NamedBsdf> c{diffuse_case(Rgb(1)), diffuse_case(Rgb(0))};
  // Alphas: delta, just below and at the smooth threshold, and the roughest a user can ask for.
  for (float alpha : {0.0f, 9.9e-5f, 1e-4f, 1e-3f, 0.05f, 1.0f}) {
    c.push_back(conductor_case(alpha));
    c.push_back(mirror_case(alpha));
    for (float ior : {1.0f, 1.0001f, 1.33f, 4.0f, 0.25f}) c.push_back(dielectric_case(ior, alpha));
  }
  return c;
}

std::string sanitize_name(std::string name) {
  for (char &ch : name)
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  return name;
}

}  // namespace nimbus::test
