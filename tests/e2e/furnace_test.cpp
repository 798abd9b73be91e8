// Furnace tests: a diffuse sphere inside a large sphere that emits radiance 1 from both sides and
// absorbs everything. Lit by radiance 1 from every direction, a convex Lambertian object of albedo a
// reflects radiance a in every direction, so every pixel's expected value is known exactly: 1 where
// the camera sees the emitter, a where it sees the sphere. Any energy lost or gained by the path tracer
// (MIS weights, light pdfs, two-sided emission, BSDF sampling, Russian roulette) shows up as a bias.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "e2e_support.hpp"
#include "scene/scene_parser.hpp"

namespace nimbus::e2e {
namespace furnace_test {

constexpr uint32_t kBlock = 8;
// How many standard errors an 8x8 block mean may stray; with ~40 blocks and 3 channels a correct
// renderer exceeds 5 with probability ~1e-5.
constexpr double kSigmas = 5;

enum class Sees { Sphere, Emitter, Edge };  // what a pixel's whole footprint sees

// Classifies every pixel of `scene`'s camera: its footprint lies wholly inside the small sphere's image,
// wholly outside it, or straddles the outline. The camera looks at the sphere's centre, so the sphere's
// image on the plane z = 1 of camera space is a disc of radius tan(asin(r / d)) around the axis.
std::vector<Sees> coverage(const SceneDesc &scene) {
  const ShapeDesc &sphere = scene.shapes.at(0);
  const CameraDesc &cam = scene.camera;
  const float dist = length(sphere.center - cam.position);
  EXPECT_LT(length(cam.look_at - sphere.center), 1e-6f)
      << "the classification assumes the camera aims at the sphere";
  const double disc = sphere.radius / std::sqrt(double(dist) * dist - double(sphere.radius) * sphere.radius);
  const uint32_t w = scene.render.width, h = scene.render.height;
  // The camera model of host/world/camera.hpp: horizontal fov across the width, square pixels.
  const double tan_half = std::tan(cam.fov_degrees * M_PI / 360), aspect = double(h) / w;
  const auto sx = [&](double fx) { return (2 * fx / w - 1) * tan_half; };
  const auto sy = [&](double fy) { return (1 - 2 * fy / h) * tan_half * aspect; };
  std::vector<Sees> out(size_t(w) * h);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      const double x0 = sx(x), x1 = sx(x + 1), y0 = sy(y + 1), y1 = sy(y);
      const double far =
          std::hypot(std::max(std::abs(x0), std::abs(x1)), std::max(std::abs(y0), std::abs(y1)));
      const double near = std::hypot(std::clamp(0.0, x0, x1), std::clamp(0.0, y0, y1));
      out[size_t(y) * w + x] = far < disc * (1 - 1e-3)    ? Sees::Sphere
                               : near > disc * (1 + 1e-3) ? Sees::Emitter
                                                          : Sees::Edge;
    }
  return out;
}

struct Furnace {
  SceneDesc scene;
  ImageLayers image;
  std::vector<Sees> sees;
};

std::optional<Furnace> render_furnace(const TestDir &dir, const std::string &name) {
  auto parsed = parse_scene_file(scene(name));
  if (!parsed) {
    ADD_FAILURE() << parsed.error().message;
    return std::nullopt;
  }
  const std::string exr = dir.file("furnace.exr");
  const ProcessResult r = run_nimbus({"render", scene(name), "-o", exr, "-q"}, dir);
  if (!exited_with(r, 0)) {
    ADD_FAILURE() << r.describe();
    return std::nullopt;
  }
  auto img = read_exr(exr);
  if (!img) return std::nullopt;
  Furnace f{std::move(parsed.value()), std::move(*img), {}};
  f.sees = coverage(f.scene);
  EXPECT_EQ(f.image.width, f.scene.render.width);
  EXPECT_EQ(f.image.height, f.scene.render.height);
  return f;
}

// Checks one channel against per-pixel expectations (NaN = unknown, skipped): the emitter seen directly
// is exact; the sphere region's mean is within 1%; every 8x8 block's mean over its known pixels is within
// kSigmas standard errors and 5%. The per-pixel standard deviation comes from the spread of the sphere's
// pixels around their known expected value (each pixel is an independent estimate).
void check_channel(const Furnace &f, const std::string &channel, const std::vector<double> &expected) {
  SCOPED_TRACE("channel " + channel);
  const std::vector<float> &px = plane(f.image, channel);
  ASSERT_EQ(px.size(), expected.size());
  double sphere_sum = 0, sphere_expected = 0, sq = 0, worst_emitter = 0;
  size_t sphere_n = 0, noisy_n = 0;
  for (size_t i = 0; i < px.size(); ++i) {
    ASSERT_TRUE(std::isfinite(px[i])) << "pixel " << i;
    if (std::isnan(expected[i])) continue;
    const double err = px[i] - expected[i];
    if (f.sees[i] == Sees::Emitter) {
      worst_emitter = std::max(worst_emitter, std::abs(err));
      continue;
    }
    sq += err * err, ++noisy_n;
    if (f.sees[i] == Sees::Sphere) sphere_sum += px[i], sphere_expected += expected[i], ++sphere_n;
  }
  // Camera rays that hit the emitter return its radiance exactly.
  EXPECT_LE(worst_emitter, 1e-4);
  ASSERT_GT(sphere_n, 300u) << "the sphere should cover a large part of the image";
  EXPECT_NEAR(sphere_sum / sphere_n, sphere_expected / sphere_n, 0.01 * sphere_expected / sphere_n);
  const double pixel_var = sq / double(noisy_n);

  const uint32_t w = f.image.width, h = f.image.height;
  for (uint32_t by = 0; by + kBlock <= h; by += kBlock)
    for (uint32_t bx = 0; bx + kBlock <= w; bx += kBlock) {
      double sum = 0, want = 0;
      size_t known = 0, noisy = 0;
      for (uint32_t y = by; y < by + kBlock; ++y)
        for (uint32_t x = bx; x < bx + kBlock; ++x) {
          const size_t i = size_t(y) * w + x;
          if (std::isnan(expected[i])) continue;
          sum += px[i], want += expected[i], ++known;
          noisy += f.sees[i] != Sees::Emitter;
        }
      if (known < kBlock) continue;  // too few known pixels for a meaningful mean
      const double mean = sum / known, target = want / known;
      const double se = std::sqrt(pixel_var * noisy) / known;
      EXPECT_LE(std::abs(mean - target), std::max(kSigmas * se, 1e-4))
          << "block (" << bx << ", " << by << "): mean " << mean << ", expected " << target << ", std error "
          << se;
      EXPECT_LE(std::abs(mean - target), 0.05 * target) << "block (" << bx << ", " << by << ")";
    }
}

TEST(Furnace, WhiteSphereInUniformEmitterIsOneEverywhere) {
  TestDir dir;
  const auto f = render_furnace(dir, "furnace_white.yaml");
  ASSERT_TRUE(f);
  ASSERT_GE(f->scene.render.max_depth, 64u);
  const std::vector<double> expected(f->sees.size(), 1.0);  // the outline too: both sides are 1
  for (const char *c : {"R", "G", "B"}) {
    const std::vector<float> &px = plane(f->image, c);
    double sum = 0;
    for (float v : px) sum += v;
    EXPECT_NEAR(sum / double(px.size()), 1.0, 0.01) << c;
    check_channel(*f, c, expected);
  }
}

TEST(Furnace, GreySphereReflectsHalfAndEmitterStaysOne) {
  TestDir dir;
  const auto f = render_furnace(dir, "furnace_grey.yaml");
  ASSERT_TRUE(f);
  const float albedo = f->scene.materials.at(f->scene.shapes.at(0).material).albedo.x;
  ASSERT_EQ(albedo, 0.5f);
  std::vector<double> expected(f->sees.size());
  for (size_t i = 0; i < expected.size(); ++i)
    expected[i] = f->sees[i] == Sees::Sphere ? albedo : f->sees[i] == Sees::Emitter ? 1.0 : NAN;
  for (const char *c : {"R", "G", "B"}) check_channel(*f, c, expected);
}

}  // namespace furnace_test
}  // namespace nimbus::e2e
