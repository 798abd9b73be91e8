// Textured renders, in process with the real plugins: a checker quad shows the checker (upright, colours
// decoded to linear), and a normal map changes the shading as its tilt says, with the cosine taken about
// the mapped normal. A scene without textures builds no texture system at all.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "support/render_support.hpp"
#include "texture_fixtures.hpp"
#include "world/world.hpp"

namespace nimbus {
namespace render_test {

using testing::region_mean;
using testing::RenderRequest;
using testing::SceneRenderer;
using texture_test::ScratchDir;

constexpr int kSize = 48;
// The camera looks down at a 2x2 quad in the z = 0 plane (u along +x, v along +y) and sees x, y in
// [-kHalfView, kHalfView]: +x to the right and +y up in the image.
constexpr float kHalfView = 0.9f;

std::string camera_and_quad(const std::string &material) {
  const float distance = kHalfView / std::tan(radians(22.5f));
  return "render: { resolution: [" + std::to_string(kSize) + ", " + std::to_string(kSize) +
         "], max_depth: 4 }\n" + "camera: { position: [0, 0, " + std::to_string(distance) +
         "], look_at: [0, 0, 0], up: [0, 1, 0], fov: 45 }\n" + "materials:\n  quad: " + material +
         "\n  black: { type: diffuse, albedo: 0 }\n" +
         "objects:\n  - { shape: rectangle, size: [2, 2], material: quad }\n";
}

constexpr uint8_t kA[3] = {188, 188, 188};
constexpr uint8_t kB[3] = {32, 96, 160};

// The expected albedo at texture coordinates (s, t): bilinear between the decoded texels of the 2x2 checker,
// periodic, written independently of the texture code.
Rgb checker_albedo(double s, double t) {
  const auto lin = [](const uint8_t c[3]) {
    return Rgb{float(texture_test::srgb8_to_linear(c[0])), float(texture_test::srgb8_to_linear(c[1])),
               float(texture_test::srgb8_to_linear(c[2]))};
  };
  const double x = s * 2 - 0.5, y = t * 2 - 0.5;
  const double x0 = std::floor(x), y0 = std::floor(y);
  Rgb sum(0.0f);
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      const double w = (i ? x - x0 : 1 - (x - x0)) * (j ? y - y0 : 1 - (y - y0));
      const int tx = ((int(x0) + i) % 2 + 2) % 2, ty = ((int(y0) + j) % 2 + 2) % 2;
      sum += lin(tx == ty ? kA : kB) * float(w);
    }
  return sum;
}

// The same region's expected mean: the quad's albedo averaged over the pixels' areas.
Rgb expected_mean(int x0, int x1, int y0, int y1) {
  Rgb sum(0.0f);
  constexpr int kSub = 8;
  for (int y = y0 * kSub; y < y1 * kSub; ++y)
    for (int x = x0 * kSub; x < x1 * kSub; ++x) {
      const double wx = ((x + 0.5) / (kSize * kSub) * 2 - 1) * kHalfView;
      const double wy = (1 - (y + 0.5) / (kSize * kSub) * 2) * kHalfView;
      const double u = (wx + 1) / 2, v = (wy + 1) / 2;
      sum += checker_albedo(u, 1 - v);
    }
  return sum / float((x1 - x0) * (y1 - y0) * kSub * kSub);
}

TEST(TexturedRender, CheckerQuadShowsTheChecker) {
  ScratchDir dir;
  texture_test::write_checker_png(dir.file("checker.png"), kA, kB);
  // A furnace: inside a sphere emitting radiance 1 the quad's radiance is its albedo.
  const std::string yaml =
      camera_and_quad("{ type: diffuse, albedo: { texture: " + dir.file("checker.png") + " } }") +
      "  - { shape: sphere, center: [0, 0, 0], radius: 10, material: black, two_sided: true,\n"
      "      emission: { radiance: [1, 1, 1] } }\n";
  SceneRenderer r;
  RenderRequest req;
  req.iterations = 64;
  const ImageLayers img = r.render(yaml, req);
  ASSERT_EQ(img.width, uint32_t(kSize));
  const int h = kSize / 2;
  const int quadrants[4][4] = {{0, h, 0, h}, {h, kSize, 0, h}, {0, h, h, kSize}, {h, kSize, h, kSize}};
  for (const auto &q : quadrants) {
    const Rgb got = region_mean(img, q[0], q[1], q[2], q[3]), want = expected_mean(q[0], q[1], q[2], q[3]);
    std::printf("quadrant x [%d, %d) y [%d, %d): rendered (%.4f %.4f %.4f), expected (%.4f %.4f %.4f)\n",
                q[0], q[1], q[2], q[3], got.x, got.y, got.z, want.x, want.y, want.z);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c] / want[c], 1.0, 0.02) << "channel " << c;
  }
  // The checker itself, upright: the top-left texel (A, grey) at the top left of the image, B (blue) to
  // its right.
  const Rgb tl = region_mean(img, 0, h, 0, h), tr = region_mean(img, h, kSize, 0, h);
  EXPECT_GT(tl.x, 1.5f * tr.x);
  EXPECT_GT(tl.y, 1.2f * tr.y);
}

// Seen from straight above and lit by a distant point light straight above (irradiance pi), a diffuse quad
// of albedo 0.8 has radiance 0.8 |cos| about its shading normal.
std::string lit_quad(const std::string &material) {
  return camera_and_quad(material) +
         "lights:\n  - { type: point, position: [0, 0, 100], intensity: " + std::to_string(10000 * kPi) +
         " }\n";
}

TEST(TexturedRender, NormalMapTiltsTheShading) {
  ScratchDir dir;
  const auto uniform_map = [&](const std::string &name, Vec3f n) {
    const Rgb texel = n * 0.5f + Vec3f(0.5f);
    std::vector<float> px;
    for (int i = 0; i < 4; ++i) px.insert(px.end(), {texel.x, texel.y, texel.z});
    texture_test::write_exr(dir.file(name), 2, 2, 3, px);
    return dir.file(name);
  };
  const float t = radians(60);
  const std::string flat = uniform_map("flat.exr", {0, 0, 1});
  const std::string tilted = uniform_map("tilted.exr", {std::sin(t), 0, std::cos(t)});

  SceneRenderer r;
  RenderRequest req;
  req.iterations = 4;
  const ImageLayers plain = r.render(lit_quad("{ type: diffuse, albedo: 0.8 }"), req);
  const ImageLayers with_flat =
      r.render(lit_quad("{ type: diffuse, albedo: 0.8, normal_map: " + flat + " }"), req);
  const ImageLayers with_tilt =
      r.render(lit_quad("{ type: diffuse, albedo: 0.8, normal_map: " + tilted + " }"), req);
  const int q = kSize / 4;
  const Rgb p = region_mean(plain, q, 3 * q, q, 3 * q), f = region_mean(with_flat, q, 3 * q, q, 3 * q),
            m = region_mean(with_tilt, q, 3 * q, q, 3 * q);
  std::printf("centre radiance: plain %.5f, flat map %.5f, 60-degree map %.5f\n", p.x, f.x, m.x);
  EXPECT_NEAR(p.x, 0.8f, 0.01f);
  // The flat map shades exactly as no map at all, pixel for pixel.
  const std::vector<float> &a = plain.layers.at("beauty").data, &b = with_flat.layers.at("beauty").data;
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i)
    ASSERT_NEAR(a[i], b[i], 1e-5f * std::max(1.0f, a[i])) << "value " << i;
  // cos 60 = 1/2: without the mapped cosine the integrator's |wi.ns| = 1 would leave 0.8.
  EXPECT_NEAR(m.x / p.x, 0.5f, 0.01f);
}

TEST(TexturedRender, LightTracerAgreesOnNormalMappedShading) {
  // Importance transport goes through the adjoint form of the same correction: the light tracer and the
  // path tracer must agree on a normal-mapped quad under a near point light (which lights it unevenly).
  ScratchDir dir;
  const float t = radians(60);
  const Rgb texel = Vec3f{std::sin(t), 0, std::cos(t)} * 0.5f + Vec3f(0.5f);
  std::vector<float> px;
  for (int i = 0; i < 4; ++i) px.insert(px.end(), {texel.x, texel.y, texel.z});
  texture_test::write_exr(dir.file("tilted.exr"), 2, 2, 3, px);
  const std::string yaml =
      camera_and_quad("{ type: diffuse, albedo: 0.8, normal_map: " + dir.file("tilted.exr") + " }") +
      "lights:\n  - { type: point, position: [-0.5, 0.3, 1.5], intensity: 3 }\n";
  SceneRenderer r;
  RenderRequest req;
  req.iterations = 64;
  req.integrator = "nimbus.pt";
  const Rgb pt = testing::mean_rgb(r.render(yaml, req).layers.at("beauty").data);
  req.integrator = "nimbus.lt";
  const Rgb lt = testing::mean_rgb(r.render(yaml, req).layers.at("beauty").data);
  std::printf("image mean with the 60-degree map: path tracer %.5f, light tracer %.5f\n", pt.x, lt.x);
  EXPECT_NEAR(lt.x / pt.x, 1.0f, 0.03f);
}

TEST(TexturedRender, UntexturedSceneOpensNoTextureSystem) {
  auto desc = parse_scene_string(lit_quad("{ type: diffuse, albedo: 0.8 }"), "plain.yaml");
  ASSERT_TRUE(desc.ok()) << desc.error().message;
  auto world = World::build(desc.value(), desc->render.filter);
  ASSERT_TRUE(world.ok()) << world.error().message;
  EXPECT_EQ(world.value()->textures, nullptr);
}

}  // namespace render_test
}  // namespace nimbus
