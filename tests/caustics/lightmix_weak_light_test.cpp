// A weak light keeps its caustic and its LightMix layer (caustics solver spec 6.1, 8): two glass balls
// mirror-symmetric about x = 0, each under its own point light, intensities R and 1 (R = 10^4 and 10^9),
// in their own LightMix groups. With LightMix requested, NEE and photon emission keep a share per group,
// so the weak layer scaled by R and mirrored estimates the strong layer, and converges as fast.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "support/render_support.hpp"

namespace nimbus::testing {
namespace lightmix_weak_light_test {

constexpr int kWidth = 64, kHeight = 32;

const char *kSceneTemplate = R"(
render: { resolution: [64, 32], max_depth: 8 }
camera: { position: [0, 0, 4.2], look_at: [0, 0, 0], up: [0, 1, 0], fov: 70 }
materials:
  floor: { type: diffuse, albedo: [0.6, 0.6, 0.6] }
  glass: { type: dielectric, ior: 1.5 }
objects:
  - { shape: rectangle, size: [8, 8], material: floor }
  - { shape: sphere, center: [-1.2, 0, 0.3], radius: 0.3, material: glass }
  - { shape: sphere, center: [1.2, 0, 0.3], radius: 0.3, material: glass }
lights:
  - { type: point, position: [-2.6, 0, 0.9], intensity: [STRONG, STRONG, STRONG], group: strong }
  - { type: point, position: [2.6, 0, 0.9], intensity: [1, 1, 1], group: weak }
)";

// The scene with the strong light's intensity `ratio`.
std::string scene(double ratio) {
  char strong[64];
  std::snprintf(strong, sizeof strong, "%.17g", ratio);
  std::string s = kSceneTemplate;
  for (size_t at; (at = s.find("STRONG")) != std::string::npos;) s.replace(at, 6, strong);
  return s;
}

// Luminance of a layer, and of the other layer mirrored in x and scaled: the weak layer's estimate of
// the strong one.
std::vector<double> lum(const ImageLayers &img, const std::string &layer, bool mirror, double scale) {
  const std::vector<float> &d = img.layers.at(layer).data;
  std::vector<double> out(size_t(kWidth) * kHeight);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const int sx = mirror ? kWidth - 1 - x : x;
      out[size_t(y) * kWidth + x] = scale * luminance(Rgb::load(&d[3 * (size_t(y) * kWidth + sx)]));
    }
  return out;
}

// Mean over columns [x0, x1) of the rows around the balls' centre line (12-19).
double mean_of(const std::vector<double> &v, int x0, int x1) {
  double s = 0;
  for (int y = 12; y < 20; ++y)
    for (int x = x0; x < x1; ++x) s += v[size_t(y) * kWidth + x];
  return s / double((x1 - x0) * 8);
}

double rel_mse(const std::vector<double> &a, const std::vector<double> &b) {
  double s = 0;
  for (size_t i = 0; i < a.size(); ++i) s += (a[i] - b[i]) * (a[i] - b[i]) / (b[i] * b[i] + 0.01);
  return s / double(a.size());
}

class CausticsLightMix : public ::testing::TestWithParam<double> {};

TEST_P(CausticsLightMix, WeakLightLayerConvergesLikeTheStrongOne) {
  const double kRatio = GetParam();
  const std::string kScene = scene(kRatio);
  // Both layers in units of a strong light of 10^4, so that relMSE's offset (0.01) weighs the dark pixels
  // alike at every ratio: at 10^9 it would vanish, and pixels 10^5 times darker than the focus beside
  // them, whose light the merge kernel's edge catches or misses, would weigh as much as the caustic.
  const double unit = 1e4 / kRatio;
  SceneRenderer r;
  const auto render = [&](uint64_t iterations, uint64_t seed) {
    RenderRequest q;
    q.integrator = "nimbus.caustics";
    q.iterations = iterations;
    q.seed = seed;
    q.elements = {"lightmix"};
    return r.render(kScene, q);
  };
  // The caustic of the strong light's ball (x ~ -0.5 m, beyond the ball seen from the light: pixel
  // columns 22-29 on the side where the strong layer is brighter there), the strong layer against the
  // weak layer x 10^4 mirrored, over 8 seeds at 64 iterations; relMSE over the whole image.
  std::vector<double> strong, weak, err_few, err_many;
  std::vector<std::vector<double>> strong_images;
  for (uint64_t seed = 1; seed <= 8; ++seed) {
    const auto img = render(64, seed);
    const auto s = lum(img, "lightmix.strong", false, unit),
               w = lum(img, "lightmix.weak", true, kRatio * unit);
    const int x0 = mean_of(s, 22, 30) > mean_of(s, kWidth - 30, kWidth - 22) ? 22 : kWidth - 30;
    strong.push_back(mean_of(s, x0, x0 + 8));
    weak.push_back(mean_of(w, x0, x0 + 8));
    err_many.push_back(rel_mse(w, s));
    strong_images.push_back(s);
    const auto few = render(16, seed + 10);
    err_few.push_back(
        rel_mse(lum(few, "lightmix.weak", true, kRatio * unit), lum(few, "lightmix.strong", false, unit)));
  }
  const auto [ms, ses] = mean_and_se(strong);
  const auto [mw, sew] = mean_and_se(weak);
  std::sort(err_few.begin(), err_few.end());
  std::sort(err_many.begin(), err_many.end());
  const double few = 0.5 * (err_few[3] + err_few[4]), many = 0.5 * (err_many[3] + err_many[4]);
  // The strong layer's own noise: relMSE between two of its renders (2 var_s).
  const double strong_noise = rel_mse(strong_images[0], strong_images[1]);
  std::printf(
      "ratio %.0e, strong caustic: strong layer %.5g (SE %.5g), weak layer x ratio mirrored %.5g (SE %.5g); "
      "relMSE between them (median of 8) %.4g at 16 iterations, %.4g at 64; between two strong "
      "renders %.4g\n",
      kRatio, ms, ses, mw, sew, few, many, strong_noise);
  // 3 sigma of the difference of the two means, each over 8 seeds: with standard errors estimated from 8
  // samples, the 99.73 % two-sided quantile of Student's t with 7 degrees of freedom, 4.03 of them.
  EXPECT_NEAR(mw, ms, 4.03 * std::hypot(ses, sew));
  // The weak layer converges at the strong one's rate: NEE and photons choose the weak light with
  // probability 1/4 against 3/4 for the strong one, so var_w ~ 3 var_s and relMSE(weak, strong) = var_w +
  // var_s ~ 2x the strong-strong figure (2 var_s); 4x allows for the heavy tails of 64-iteration renders.
  EXPECT_LT(many, 4 * strong_noise);
  // Both layers' noise falls as 1/iterations (4x here); 2x leaves room for the photon map's slower start.
  // Medians of 8 renders: with 4, one heavy-tailed render decides the figure (it ranges over 2-5x).
  EXPECT_GT(few / many, 2.0);
}

INSTANTIATE_TEST_SUITE_P(PowerRatios, CausticsLightMix, ::testing::Values(1e4, 1e9));

}  // namespace lightmix_weak_light_test
}  // namespace nimbus::testing
