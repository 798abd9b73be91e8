// IOR and roughness extremes in a furnace: the object sits inside a sphere that emits radiance 1 from
// both sides and absorbs everything, so every path that ends ends with radiance 1 and each pixel is the
// object's end-to-end albedo along that view. Lossless smooth dielectrics (radiance compressed by 1/eta^2
// on the way in and expanded by eta^2 on the way out) and ideal mirrors keep every pixel at exactly 1 in
// expectation; single-scattering GGX loses the energy that would bounce between microfacets, so rough
// cases may only lose, never gain, and keep at least a floor computed independently of the renderer. No
// NaN or Inf may reach the film in any case.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

#include "extremes_support.hpp"
#include "furnace_support.hpp"
#include "glass_furnace_model.hpp"

namespace nimbus::extremes {
namespace furnace_test {

struct Glass {
  float ior, roughness;
};
void PrintTo(const Glass &g, std::ostream *os) { *os << "ior " << g.ior << ", roughness " << g.roughness; }

// Inside the glass the path throughput is 1/eta^2, so Russian roulette kills most paths and boosts the
// rest: the noise grows with the IOR. These counts keep the image mean's standard error near 0.2 %, so
// the 1 % bound sits at about five standard errors.
uint64_t iterations_for(float ior) { return ior < 2 ? 64 : ior < 3 ? 192 : 512; }

std::string glass_name(const ::testing::TestParamInfo<Glass> &info) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "ior%g_r%g", info.param.ior, info.param.roughness);
  std::string n = buf;
  for (char &c : n)
    if (c == '.') c = 'p';
  return n;
}

// A glass sphere and, in front of its lower half, a tilted glass slab: refraction at every angle,
// total internal reflection at the slab's edges and interreflection between the two.
std::string glass_furnace(const Glass &g) {
  return furnace_scene("{ type: dielectric, ior: " + num(g.ior) + ", roughness: " + num(g.roughness) + " }",
                       "  - { shape: box, size: [1.6, 0.25, 0.7], material: object,\n"
                       "      transform: { rotate: [25, 0, 10], translate: [0.2, -1.7, -0.6] } }\n");
}

class SmoothGlass : public ::testing::TestWithParam<Glass> {};

// Lossless: the image is 1 everywhere. Fresnel-chosen delta lobes have weight exactly 1; only Russian
// roulette inside the glass adds noise.
TEST_P(SmoothGlass, KeepsEveryPixelAtTheEmitterRadiance) {
  SceneRenderer r;
  const Rendered img = render(r, glass_furnace(GetParam()), pt(iterations_for(GetParam().ior), 21));
  ASSERT_TRUE(img.ok);
  EXPECT_EQ(img.nonfinite, 0u);
  expect_furnace_level(img, 1.0, 0.01);
}

// Roughness 0.001 is alpha 1e-6: below the smooth threshold, it must behave exactly like roughness 0.
INSTANTIATE_TEST_SUITE_P(Extremes, SmoothGlass,
                         ::testing::Values(Glass{1.0001f, 0}, Glass{1.33f, 0}, Glass{2.4f, 0}, Glass{4, 0},
                                           Glass{1.0001f, 0.001f}, Glass{1.33f, 0.001f}, Glass{2.4f, 0.001f},
                                           Glass{4, 0.001f}),
                         glass_name);

class RoughGlass : public ::testing::TestWithParam<Glass> {};

// The floor is glass_furnace_model.hpp's independent lower bound of each pixel (256 paths a pixel),
// averaged, less five standard errors of the mean pixel difference between image and model; that error
// comes from the spread of the differences, which overstates the noise (the model's own noise and its
// varying gap below the pixels add to it), so the floor errs low. The same model weighted with the
// height-correlated masking-shadowing estimates the image itself: the image mean must match it within five
// standard errors of their difference and 1e-4 (float rounding, where index-matched glass leaves no noise).
// Roughness 0.0101 is alpha 1.02e-4, just above the smooth threshold (GGX's D peaks near 3e7 there): it
// must lose almost nothing. At roughness 1 even ior 1.0001 loses ~28 %: single-scattering GGX drops the
// light that masking stops, whatever the IOR (tests/materials/energy_test.cpp checks the same per bounce).
void expect_glass_furnace(const Glass &g, bool slab, const Rendered &img) {
  const double alpha = double(g.roughness) * g.roughness;
  const std::vector<double> bound =
      glass_furnace_lower_bound(g.ior, alpha, slab, img.width, img.height, 256, 7);
  const std::vector<double> model = glass_furnace_expected(g.ior, alpha, slab, img.width, img.height, 256, 7);
  const auto mean_of = [&](const std::vector<double> &v) {
    return estimate(img.width, img.height, [&](uint32_t x, uint32_t y) { return v[y * img.width + x]; }).mean;
  };
  const auto difference = [&](const std::vector<double> &v, int c) {
    return estimate(img.width, img.height,
                    [&](uint32_t x, uint32_t y) { return img.at(x, y, c) - v[y * img.width + x]; });
  };
  double error = 0;
  for (int c = 0; c < 3; ++c) error = std::max(error, difference(bound, c).std_error);
  const double floor = mean_of(bound) - 5 * error;
  if (verbose())
    std::printf("  ior %g roughness %g: lower bound %.4f, floor %.4f, expected %.4f\n", g.ior, g.roughness,
                mean_of(bound), floor, mean_of(model));
  expect_furnace_bounded(img, floor);
  for (int c = 0; c < 3; ++c) {
    const Estimate d = difference(model, c);
    EXPECT_NEAR(d.mean, 0, 5 * d.std_error + 1e-4)
        << "channel " << c << ": image " << d.mean + mean_of(model) << ", model " << mean_of(model);
  }
}

TEST_P(RoughGlass, NeverGainsAndLosesNoMoreThanTheFloor) {
  SceneRenderer r;
  const Rendered img = render(r, glass_furnace(GetParam()), pt(iterations_for(GetParam().ior), 23));
  ASSERT_TRUE(img.ok);
  EXPECT_EQ(img.nonfinite, 0u);
  expect_glass_furnace(GetParam(), true, img);
}

INSTANTIATE_TEST_SUITE_P(Extremes, RoughGlass,
                         ::testing::Values(Glass{1.0001f, 0.0101f}, Glass{1.33f, 0.0101f},
                                           Glass{2.4f, 0.0101f}, Glass{4, 0.0101f}, Glass{1.0001f, 0.5f},
                                           Glass{1.33f, 0.5f}, Glass{2.4f, 0.5f}, Glass{4, 0.5f},
                                           Glass{1.0001f, 1}, Glass{1.33f, 1}, Glass{2.4f, 1}, Glass{4, 1}),
                         glass_name);

// The furnace again with a uniform environment of radiance 1 instead of the emitter sphere: environment
// sampling at extreme IORs (the escaping ray's radiance now comes from eval_infinite and its MIS pdf).
TEST(EnvironmentFurnace, SmoothGlassStaysAtOneAndRoughGlassNeverGains) {
  for (const Glass g : {Glass{2.4f, 0}, Glass{4, 0}, Glass{1.33f, 1}}) {
    const std::string scene = R"(
render: { resolution: [24, 24], seed: 1, max_depth: 128 }
camera: { position: [0, -3, 0], look_at: [0, 0, 0], up: [0, 0, 1], fov: 40 }
materials:
  object: { type: dielectric, ior: )" +
                              num(g.ior) + ", roughness: " + num(g.roughness) + R"( }
objects:
  - { shape: sphere, center: [0, 0, 0], radius: 1, material: object }
environment: { color: [1, 1, 1] }
)";
    SCOPED_TRACE("ior " + num(g.ior) + ", roughness " + num(g.roughness));
    NIMBUS_ASSERT_PARSES(scene, "a uniform environment");
    SceneRenderer r;
    const Rendered img = render(r, scene, pt(iterations_for(g.ior), 25));
    ASSERT_TRUE(img.ok);
    EXPECT_EQ(img.nonfinite, 0u);
    if (g.roughness == 0)
      expect_furnace_level(img, 1.0, 0.01);
    else
      expect_glass_furnace(g, false, img);
  }
}

}  // namespace furnace_test
}  // namespace nimbus::extremes
