// The camera's thin lens and the pixel filters in real renders through the CLI, measured on vertical
// edges of emitters against black (edge_profile.hpp): emission seen directly (max_depth 1) is exact, so
// a pixel's only randomness is where its samples land, and the expected profile across an edge follows
// from the kernels that blur it. Every column must match its prediction within kSigmas standard errors
// and so must the edge's width (the second moment of its line spread, in pixels).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "edge_profile.hpp"

namespace nimbus::e2e {
namespace optics_test {

// With ~20 columns and one width per edge a correct renderer exceeds 5 sigma with probability < 1e-5.
constexpr double kSigmas = 5;
// Columns wholly on one side agree in every row (their standard error is 0); a filter's weights there
// average to 1 only up to the normalisation of its 64 x 64 sampling table (< 1e-3, pixel_filter.cpp).
constexpr double kSlack = 2e-3;

// The box filter's offset: uniform over the pixel.
Kernel box() {
  return Kernel::of(0.5, [](double) { return 1.0; });
}

// Depth of field. Camera at the origin looking along +y, fov 90 (tan of half the view 1), 64 x 48
// pixels: a tan of 1 / 32 is one pixel. A near emitter at depth 2 = focus_distance fills the top rows left
// of film x 40.4; a far one at depth 6 fills the bottom rows left of film x 24.7. A thin lens of radius A
// focused at f spreads a point at depth z over a disk of radius A |1/f - 1/z| in tan units, so the far
// edge is blurred by R = A (1/2 - 1/6) 32 = 3 px and the near one not at all (the box filter's pixel
// only). look_at is 10 away, so a renderer that ignored focus_distance would blur the near edge instead.
constexpr double kAperture = 0.28125, kNearEdge = 40.4, kFarEdge = 24.7;
constexpr double kBlur = kAperture * (1.0 / 2 - 1.0 / 6) * 32;

std::string lens_scene(double aperture) {
  char camera[200];
  std::snprintf(
      camera, sizeof camera,
      "camera: { position: [0, 0, 0], look_at: [0, 10, 0], up: [0, 0, 1], fov: 90, aperture: %.17g, "
      "focus_distance: 2 }\n",
      aperture);
  // The near edge at x = 2 (40.4 / 32 - 1), the far one at x = 6 (24.7 / 32 - 1); rectangles face -y.
  char objects[600];
  std::snprintf(
      objects, sizeof objects,
      "objects:\n"
      "  - { shape: rectangle, size: [%.17g, 2], material: lamp, emission: { radiance: [1, 1, 1] },\n"
      "      transform: { rotate: [90, 0, 0], translate: [%.17g, 2, 1.15] } }\n"
      "  - { shape: rectangle, size: [%.17g, 6], material: lamp, emission: { radiance: [1, 1, 1] },\n"
      "      transform: { rotate: [90, 0, 0], translate: [%.17g, 6, -3] } }\n",
      2 * (kNearEdge / 32 - 1) + 3, (2 * (kNearEdge / 32 - 1) - 3) / 2, 6 * (kFarEdge / 32 - 1) + 9,
      (6 * (kFarEdge / 32 - 1) - 9) / 2);
  return std::string(
             "render: { resolution: [64, 48], iterations: 256, seed: 5, max_depth: 1, integrator: nimbus.pt "
             "}\n") +
         camera + "materials:\n  lamp: { type: diffuse, albedo: [0, 0, 0] }\n" + objects;
}

// Rows 0-17 see only the near emitter's vertical edge (it spans z from 0.15 up, beyond the top row), rows
// 30-47 only the far one's (its top edge at z = 0 blurs rows 21-27; rays of row 30 pass z = -0.375 at the
// focus plane and stay below 0 to depth 6 from any point of the lens).
TEST(Optics, ThinLensBlursTheEdgeOffTheFocusPlaneByItsCircleOfConfusion) {
  TestDir dir;
  const Frame lens = render_frame(dir, "lens", lens_scene(kAperture));
  const Frame pinhole = render_frame(dir, "pinhole", lens_scene(0));
  ASSERT_EQ(lens.width, 64u);
  ASSERT_EQ(pinhole.width, 64u);
  const Kernel pixel = box(), far = box().plus(disk_marginal(kBlur));
  // In focus: as sharp as through a pinhole.
  const double near_w =
      expect_edge(measure_edge(lens, kNearEdge, 34, 47, 0, 18), pixel, kNearEdge, kSigmas, kSlack);
  const double pin_w =
      expect_edge(measure_edge(pinhole, kFarEdge, 18, 31, 30, 48), pixel, kFarEdge, kSigmas, kSlack);
  // Off it: spread by the circle of confusion (predicted width sqrt(R^2 / 4 + 1 / 12) = 1.53 px).
  const double far_w =
      expect_edge(measure_edge(lens, kFarEdge, 18, 31, 30, 48), far, kFarEdge, kSigmas, kSlack);
  EXPECT_LT(near_w, 0.5);
  EXPECT_LT(pin_w, 0.5);
  EXPECT_GT(far_w, 1.3);
}

// Pixel filters (scene-format.md: box, gaussian, blackman-harris; radius 0.5, 1.5 and 2 pixels). One
// emitter at depth 1 fills the image left of film x 24.3 (fov 90, 48 x 64 pixels: a tan of 1 / 24 is a
// pixel). Each pixel averages its samples' radiance weighted by the filter around its centre, so the edge
// profile is the filter's cumulative marginal, and the emitter's flat part keeps its radiance 1.
constexpr double kEdge = 24.3;

std::string filter_scene() {
  char objects[300];
  std::snprintf(
      objects, sizeof objects,
      "objects:\n"
      "  - { shape: rectangle, size: [%.17g, 4], material: lamp, emission: { radiance: [1, 1, 1] },\n"
      "      transform: { rotate: [90, 0, 0], translate: [%.17g, 1, 0] } }\n",
      kEdge / 24 - 1 + 3, (kEdge / 24 - 1 - 3) / 2);
  return std::string(
             "render: { resolution: [48, 64], iterations: 256, seed: 9, max_depth: 1, integrator: nimbus.pt "
             "}\n"
             "camera: { position: [0, 0, 0], look_at: [0, 1, 0], up: [0, 0, 1], fov: 90 }\n"
             "materials:\n  lamp: { type: diffuse, albedo: [0, 0, 0] }\n") +
         objects;
}

// The filters' x-marginals (the filters are products of one function of x and one of y), from their
// definitions: pbrt-v4's Gaussian shifted to reach 0 at its radius, the 4-term Blackman-Harris window.
Kernel filter_kernel(const std::string &name) {
  if (name == "gaussian") {
    const auto g = [](double t) { return std::exp(-t * t / (2 * 0.25)); };
    return Kernel::of(1.5, [g](double t) { return std::max(0.0, g(t) - g(1.5)); });
  }
  if (name == "blackman-harris")
    return Kernel::of(2.0, [](double t) {
      const double x = 2 * M_PI * (t / 2 + 1) / 2;
      return 0.35875 - 0.48829 * std::cos(x) + 0.14128 * std::cos(2 * x) - 0.01168 * std::cos(3 * x);
    });
  return box();
}

TEST(Optics, EachFilterKeepsAFlatFieldAndWidensAnEdgeByItsRadius) {
  TestDir dir;
  const std::string yaml = filter_scene();
  double width2[3] = {0, 0, 0}, width2_se[3] = {0, 0, 0};
  const char *names[3] = {"box", "gaussian", "blackman-harris"};
  for (int i = 0; i < 3; ++i) {
    SCOPED_TRACE(names[i]);
    const Frame f = render_frame(dir, names[i], yaml, {"--filter", names[i]});
    ASSERT_EQ(f.width, 48u);
    // The flat field: columns 0-19 (beyond the widest radius from the edge) of every row.
    double sum = 0, sq = 0;
    const double n = 20.0 * f.height;
    for (uint32_t y = 0; y < f.height; ++y)
      for (uint32_t x = 0; x < 20; ++x) sum += f.at(x, y), sq += f.at(x, y) * f.at(x, y);
    const double mean = sum / n, se = std::sqrt(std::max(0.0, sq / n - mean * mean) / (n - 1));
    EXPECT_NEAR(mean, 1.0, kSigmas * se + kSlack) << "flat field mean " << mean << ", SE " << se;
    // Right of the edge by more than the radius: black.
    for (uint32_t y = 0; y < f.height; ++y)
      for (uint32_t x = 28; x < f.width; ++x) ASSERT_EQ(f.at(x, y), 0.0f) << x << ", " << y;
    const EdgeProfile m = measure_edge(f, kEdge, 19, 29, 0, f.height);
    expect_edge(m, filter_kernel(names[i]), kEdge, kSigmas, kSlack);
    width2[i] = m.width2, width2_se[i] = m.width2_se;
  }
  // Wider filters widen the edge more: box < gaussian < blackman-harris, each step many standard errors.
  for (int i = 0; i < 2; ++i)
    EXPECT_GT(width2[i + 1] - width2[i], kSigmas * std::hypot(width2_se[i], width2_se[i + 1]))
        << names[i] << " vs " << names[i + 1];
}

}  // namespace optics_test
}  // namespace nimbus::e2e
