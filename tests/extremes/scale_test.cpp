// Scene scale from 1e-4 to 1e6 units, and far from the origin. Radiance does not depend on the unit of
// length, so one closed room rendered at every scale must give the same image: self-intersection (acne)
// darkens it, rays slipping through surfaces (leaks) change it, a fixed epsilon anywhere shows up at one
// end of the range. The same seed at every scale keeps the renders correlated, which makes the paired
// comparison far more sensitive than the noise of either image.
#include <gtest/gtest.h>

#include <cstdio>

#include "extremes_support.hpp"

namespace nimbus::extremes {
namespace scale_test {

// A closed white room (one box mesh, so its corners are watertight), the camera inside, a ceiling light,
// a glass and a metal sphere resting on the floor and a rotated diffuse cube on it: contact points,
// grazing wall-floor corners, refraction and glossy reflection. Every coordinate and length is
// multiplied by `s` and offset by (ox, oy, oz); radiance is not.
std::string room(double s, double ox = 0, double oy = 0, double oz = 0) {
  const auto P = [&](double x, double y, double z) { return vec(ox + s * x, oy + s * y, oz + s * z); };
  return R"(
render: { resolution: [32, 32], seed: 7, max_depth: 8 }
camera: { position: )" +
         P(0, -3.6, 1.1) + ", look_at: " + P(0, 0, 0.8) + R"(, up: [0, 0, 1], fov: 50 }
materials:
  white: { type: diffuse, albedo: [0.75, 0.75, 0.75] }
  red:   { type: diffuse, albedo: [0.63, 0.065, 0.05] }
  glass: { type: dielectric, ior: 1.5 }
  metal: { type: conductor, metal: gold, roughness: 0.25 }
  lamp:  { type: diffuse, albedo: [0, 0, 0] }
objects:
  - { shape: box, size: )" +
         vec(2 * s, 5 * s, 2 * s) + ", material: white, transform: { translate: " + P(0, -1.5, 1) + R"( } }
  - { shape: sphere, center: )" +
         P(-0.42, -0.1, 0.36) + ", radius: " + num(0.36 * s) + R"(, material: glass }
  - { shape: sphere, center: )" +
         P(0.45, 0.38, 0.36) + ", radius: " + num(0.36 * s) + R"(, material: metal }
  - { shape: box, size: )" +
         vec(0.4 * s, 0.4 * s, 0.4 * s) +
         ", material: red, transform: { rotate: [0, 0, 30], translate: " + P(0.35, -0.75, 0.2) + R"( } }
  - { shape: rectangle, size: )" +
         "[" + num(0.6 * s) + ", " + num(0.6 * s) + "]" +
         R"(, material: lamp, emission: { radiance: [17, 15, 12] },
      transform: { rotate: [180, 0, 0], translate: )" +
         P(0, 0, 1.99) + R"( } }
)";
}

constexpr uint64_t kIterations = 256;

// The unit-scale reference, rendered once per test suite (ScaleFactor inherits it).
class Scale : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    SceneRenderer r;
    reference_ = new Rendered(render(r, room(1), pt(kIterations, 1)));
  }
  static void TearDownTestSuite() {
    delete reference_;
    reference_ = nullptr;
  }
  static const Rendered &reference() { return *reference_; }

 private:
  static inline Rendered *reference_ = nullptr;
};

TEST_F(Scale, ReferenceIsLitAndFinite) {
  ASSERT_TRUE(reference().ok);
  EXPECT_EQ(reference().nonfinite, 0u);
  EXPECT_GT(channel_mean(reference(), 0).mean, 0.05) << "the room should be lit";
}

class ScaleFactor : public Scale, public ::testing::WithParamInterface<double> {};

// The strongest acne and leak detector: at every scale the image mean equals the unit-scale one.
TEST_P(ScaleFactor, ImageMatchesUnitScale) {
  ASSERT_TRUE(reference().ok);
  SceneRenderer r;
  const double s = GetParam();
  const Rendered img = render(r, room(s), pt(kIterations, 1));
  ASSERT_TRUE(img.ok);
  EXPECT_EQ(img.nonfinite, 0u) << "scale " << s;
  // Same seed, same paths: the renders differ by float rounding alone (measured: ~1e-6 relative), so
  // a floor of 1e-4 relative - or, where paths do diverge, five standard errors - is plenty.
  expect_same_image_mean(img, reference(), "scale " + num(s), 5, 1e-4);
}

std::string scale_name(const ::testing::TestParamInfo<double> &info) {
  const char *names[] = {"s1em4", "s1em2", "s1e3", "s1e6"};
  return names[info.index];
}

INSTANTIATE_TEST_SUITE_P(Extremes, ScaleFactor, ::testing::Values(1e-4, 1e-2, 1e3, 1e6), scale_name);

// The light tracer spawns its rays with its own offsets; it must be as scale-invariant as the path tracer.
// Compared with itself at unit scale (same seed), since light tracing cannot see the glass sphere's
// specular paths the way path tracing does.
// It found F4 (README.md): absolute emitter offsets and Russian roulette on the absolute photon power.
TEST(ScaleLightTracer, ImageMatchesUnitScale) {
  SceneRenderer r;
  RenderRequest req = pt(16, 1);
  req.integrator = "nimbus.lt";
  const Rendered unit = render(r, room(1), req);
  ASSERT_TRUE(unit.ok);
  EXPECT_EQ(unit.nonfinite, 0u);
  for (double s : {1e-4, 1e3, 1e6}) {
    const Rendered img = render(r, room(s), req);
    ASSERT_TRUE(img.ok);
    EXPECT_EQ(img.nonfinite, 0u) << "scale " << s;
    expect_same_image_mean(img, unit, "light tracer, scale " + num(s), 5, 1e-4);
  }
}

// Distant lights at every scale: an open scene under a sun and a uniform environment. Their radiance
// does not depend on the scene's size either, but the host bounds them by the scene's bounding sphere.
std::string open_scene(double s) {
  const auto P = [&](double x, double y, double z) { return vec(s * x, s * y, s * z); };
  return R"(
render: { resolution: [32, 32], seed: 11, max_depth: 6 }
camera: { position: )" +
         P(0, -4, 1.5) + ", look_at: " + P(0, 0, 0.4) + R"(, up: [0, 0, 1], fov: 50 }
materials:
  white: { type: diffuse, albedo: [0.7, 0.7, 0.7] }
  glass: { type: dielectric, ior: 1.5 }
  metal: { type: conductor, metal: copper, roughness: 0.3 }
objects:
  - { shape: rectangle, size: )" +
         "[" + num(8 * s) + ", " + num(8 * s) + "]" + R"(, material: white }
  - { shape: sphere, center: )" +
         P(-0.5, 0, 0.5) + ", radius: " + num(0.5 * s) + R"(, material: glass }
  - { shape: sphere, center: )" +
         P(0.7, 0.3, 0.4) + ", radius: " + num(0.4 * s) + R"(, material: metal }
lights:
  - { type: sun, direction: [-1, 2, -1.5], irradiance: [3, 3, 3], angular_diameter: 0.53 }
environment: { color: [0.3, 0.35, 0.5] }
)";
}

TEST(ScaleDistantLights, ImageMatchesUnitScale) {
  NIMBUS_ASSERT_PARSES(open_scene(1), "sun and environment lights");
  SceneRenderer r;
  const Rendered unit = render(r, open_scene(1), pt(32, 1));
  ASSERT_TRUE(unit.ok);
  EXPECT_EQ(unit.nonfinite, 0u);
  for (double s : {1e-4, 1e3, 1e6}) {
    const Rendered img = render(r, open_scene(s), pt(32, 1));
    ASSERT_TRUE(img.ok);
    EXPECT_EQ(img.nonfinite, 0u) << "scale " << s;
    expect_same_image_mean(img, unit, "distant lights, scale " + num(s), 5, 1e-4);
  }
}

// Moving the whole scene far from the origin leaves few fraction bits for its detail (7 at 1e5); the image
// must still match within noise. The paths decorrelate here, so at 256 iterations the resolution (five
// standard errors of the paired difference) is 0.5 % at 1e3 and 3 % at 1e5; measured, the offsets differ
// from the origin by at most 0.7 % (1e5) and 1.7 standard errors (1e4). The leak tests
// (leak_test.cpp, ray_leak_test.cpp) are the exact detectors.
TEST_F(Scale, FarFromOriginMatchesUnitScale) {
  ASSERT_TRUE(reference().ok);
  SceneRenderer r;
  for (double offset : {1e3, 1e4, 1e5}) {
    const Rendered img = render(r, room(1, offset, -offset, offset), pt(kIterations, 1));
    ASSERT_TRUE(img.ok);
    EXPECT_EQ(img.nonfinite, 0u) << "offset " << offset;
    expect_same_image_mean(img, reference(), "offset " + num(offset));
  }
}

}  // namespace scale_test
}  // namespace nimbus::extremes
