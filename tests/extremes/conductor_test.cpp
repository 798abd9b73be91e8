// Conductors at roughness 0 and 1 in the furnace. A convex sphere scatters each camera ray exactly once
// (a reflection never hits the sphere again; GGX reflections below the surface are the masking loss), so
// each pixel's expected value is the BSDF's directional albedo E(mu) at that pixel's viewing angle,
// averaged over the pixel. E comes from the host's own BSDF (make_bsdf, sample) in the local frame, so
// the test checks the renderer's transport - NEE, MIS, pdfs, the sphere's frame - against the material,
// including the grazing angles at the silhouette. An ideal mirror at roughness 0 is exactly 1 everywhere.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

#include "extremes_support.hpp"
#include "furnace_support.hpp"
#include "materials/bsdf.hpp"
#include "scene/scene_parser.hpp"

namespace nimbus::extremes {
namespace conductor_test {

// SplitMix64 as a uniform source: deterministic everywhere, unlike the standard distributions.
struct SplitMix {
  uint64_t s;
  float next() {
    uint64_t z = (s += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return float((z ^ (z >> 31)) >> 40) * 0x1p-24f;
  }
};

// E(mu) of `bsdf` per channel on a table of kNodes cosines, from stratified sample() calls, with each
// node's standard error.
class AlbedoTable {
 public:
  static constexpr int kNodes = 64, kSqrtSamples = 128;

  explicit AlbedoTable(const Bsdf &bsdf) {
    SplitMix rng{17};
    for (int i = 0; i < kNodes; ++i) {
      const Vec3f wo(std::sqrt(1 - sqr(mu_of(i))), 0, mu_of(i));
      double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
      for (int a = 0; a < kSqrtSamples; ++a)
        for (int b = 0; b < kSqrtSamples; ++b) {
          const Vec2f u{(a + rng.next()) / kSqrtSamples, (b + rng.next()) / kSqrtSamples};
          const BsdfSample s = bsdf.sample(wo, rng.next(), u, TransportMode::Radiance);
          if (!(s.pdf > 0)) continue;
          const Rgb w = s.f * (std::abs(s.wi.z) / s.pdf);
          for (int c = 0; c < 3; ++c) sum[c] += w[c], sum2[c] += double(w[c]) * w[c];
        }
      const double n = double(kSqrtSamples) * kSqrtSamples;
      for (int c = 0; c < 3; ++c) {
        value_[i][c] = sum[c] / n;
        // The plain-sampling error; stratification only makes the true error smaller.
        error_[i][c] = std::sqrt(std::max(0.0, sum2[c] / n - sqr(value_[i][c])) / n);
      }
    }
  }
  static float mu_of(int node) { return (node + 0.5f) / kNodes; }
  // Linear interpolation between nodes: the two nodes and their weights.
  static void weights(float mu, int &i, float &t) {
    const float x = clamp(mu * kNodes - 0.5f, 0, kNodes - 1);
    i = std::min(int(x), kNodes - 2);
    t = x - float(i);
  }
  double value(int node, int c) const { return value_[node][c]; }
  double error(int node, int c) const { return error_[node][c]; }

 private:
  double value_[kNodes][3], error_[kNodes][3];
};

// Pixels whose whole footprint sees the unit sphere, their expected value - E(mu) averaged over a 4x4
// grid of camera rays per pixel (the camera model of host/world/camera.hpp: horizontal fov, pixel
// centres at +0.5; here at (0, -3, 0) looking along +y with +z up) - and the standard error of the
// region's mean expected value that the table's own noise causes.
struct SphereExpectation {
  std::vector<char> inside;
  std::vector<double> expected[3];
  double region_error[3] = {0, 0, 0};
};

SphereExpectation sphere_expectation(const AlbedoTable &table, uint32_t w, uint32_t h, float fov_degrees) {
  SphereExpectation e;
  e.inside.assign(size_t(w) * h, 0);
  for (auto &v : e.expected) v.assign(size_t(w) * h, 0);
  std::vector<double> node_weight(AlbedoTable::kNodes, 0.0);
  size_t inside = 0;
  const float tan_half = std::tan(radians(fov_degrees) / 2), aspect = float(h) / float(w);
  const Vec3f o(0, -3, 0);
  constexpr int kSub = 4;
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      std::vector<float> mus;
      for (int j = 0; j < kSub; ++j)
        for (int i = 0; i < kSub; ++i) {
          const float fx = float(x) + (i + 0.5f) / kSub, fy = float(y) + (j + 0.5f) / kSub;
          const Vec3f d = normalize(
              Vec3f((2 * fx / float(w) - 1) * tan_half, 1, (1 - 2 * fy / float(h)) * tan_half * aspect));
          const float b = dot(o, d), disc = b * b - (length_squared(o) - 1);
          if (!(disc > 0)) continue;
          mus.push_back(-dot(d, o + d * (-b - std::sqrt(disc))));
        }
      if (mus.size() != kSub * kSub) continue;
      const size_t k = size_t(y) * w + x;
      e.inside[k] = 1, ++inside;
      for (float mu : mus) {
        int n;
        float t;
        AlbedoTable::weights(mu, n, t);
        node_weight[n] += (1 - t) / mus.size(), node_weight[n + 1] += t / mus.size();
        for (int c = 0; c < 3; ++c)
          e.expected[c][k] += (table.value(n, c) * (1 - t) + table.value(n + 1, c) * t) / mus.size();
      }
    }
  for (int c = 0; c < 3; ++c) {
    double var = 0;
    for (int n = 0; n < AlbedoTable::kNodes; ++n)
      var += sqr(float(node_weight[n] / inside * table.error(n, c)));
    e.region_error[c] = std::sqrt(var);
  }
  return e;
}

struct Metal {
  const char *name;
  const char *yaml;  // without roughness
  float roughness;
};

void PrintTo(const Metal &m, std::ostream *os) { *os << m.name << ", roughness " << m.roughness; }

class ConductorFurnace : public ::testing::TestWithParam<Metal> {};

TEST_P(ConductorFurnace, EachPixelIsTheDirectionalAlbedo) {
  const Metal &m = GetParam();
  const std::string scene =
      furnace_scene(std::string("{ type: conductor, ") + m.yaml + ", roughness: " + num(m.roughness) + " }");
  auto desc = parse_scene_string(scene, "furnace.yaml");
  ASSERT_TRUE(desc.ok()) << desc.error().message;
  const AlbedoTable table(make_bsdf(desc.value().materials.at(0)));

  SceneRenderer r;
  const Rendered img = render(r, scene, pt(128, 31));
  ASSERT_TRUE(img.ok);
  EXPECT_EQ(img.nonfinite, 0u);
  expect_furnace_bounded(img, 0);

  const SphereExpectation e =
      sphere_expectation(table, img.width, img.height, desc.value().camera.fov_degrees);
  const PixelMask inside = [&](uint32_t x, uint32_t y) { return e.inside[size_t(y) * img.width + x] != 0; };
  for (int c = 0; c < 3; ++c) {
    const auto expected = [&](uint32_t x, uint32_t y) { return e.expected[c][size_t(y) * img.width + x]; };
    const Estimate want = estimate(img.width, img.height, expected, inside);
    // Residuals against each pixel's own expectation: their spread is the render's noise alone.
    const Estimate bias = estimate(
        img.width, img.height, [&](uint32_t x, uint32_t y) { return img.at(x, y, c) - expected(x, y); },
        inside);
    ASSERT_GT(want.n, 200u) << "the sphere should fill most of the image";
    // The 4x4 footprint average and the table's interpolation are good to far better than 0.3 %.
    const double table_error = e.region_error[c];
    const double tol = 5 * std::hypot(bias.std_error, table_error) + 3e-3 * want.mean;
    if (verbose())
      std::printf("  %s r%g ch%d: sphere %.5f expected %.5f (render std error %.2g, table %.2g)\n", m.name,
                  m.roughness, c, want.mean + bias.mean, want.mean, bias.std_error, table_error);
    EXPECT_LE(std::abs(bias.mean), tol)
        << m.name << " roughness " << m.roughness << ", channel " << c << ": sphere mean "
        << want.mean + bias.mean << ", expected " << want.mean;
  }
}

INSTANTIATE_TEST_SUITE_P(Extremes, ConductorFurnace,
                         ::testing::Values(Metal{"mirror", "reflectance: [1, 1, 1]", 0},
                                           Metal{"mirror", "reflectance: [1, 1, 1]", 1},
                                           Metal{"gold", "metal: gold", 0}, Metal{"gold", "metal: gold", 1}),
                         [](const auto &info) {
                           return std::string(info.param.name) +
                                  (info.param.roughness > 0 ? "_rough1" : "_smooth");
                         });

// An ideal mirror is lossless and deterministic: every pixel, silhouette included, is exactly 1.
TEST(ConductorFurnace, SmoothIdealMirrorIsExactlyOneEverywhere) {
  SceneRenderer r;
  const Rendered img =
      render(r, furnace_scene("{ type: conductor, reflectance: [1, 1, 1], roughness: 0 }"), pt(4, 33));
  ASSERT_TRUE(img.ok);
  EXPECT_EQ(img.nonfinite, 0u);
  float worst = 0;
  for (float v : img.rgb) worst = std::max(worst, std::abs(v - 1));
  EXPECT_LE(worst, 1e-5f);
}

}  // namespace conductor_test
}  // namespace nimbus::extremes
