// In-process renders with nimbus.caustics: the switch and the zero-cost rule against nimbus.pt (bit for
// bit), render elements and LightMix layers summing to beauty, and the statistical agreement with
// nimbus.pt (area light: PT converges) and with nimbus.lt (point light: only light tracing and the
// solver see the caustic). Small images and fixed seeds keep them fast and deterministic.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "sphere_scenes.hpp"
#include "support/render_support.hpp"

namespace nimbus::testing {
namespace render_test {

const char *kAreaLight = R"(
  - { shape: rectangle, size: [0.35, 0.35], material: lamp, emission: { radiance: [110, 110, 110] }, group: key,
      transform: { rotate: [180, 0, 0], translate: [-1.4, 0, 1.9] } }
)";

// Two lights in two LightMix groups, one of them behind glass.
const char *kTwoLights = R"(
  - { shape: rectangle, size: [0.35, 0.35], material: lamp, emission: { radiance: [90, 80, 70] }, group: warm,
      transform: { rotate: [180, 0, 0], translate: [-1.4, 0, 1.9] } }
lights:
  - { type: point, position: [1.2, 1.2, 2.2], intensity: [3, 4, 6], group: cool }
)";

// No sharp material anywhere: a diffuse room with a box in it.
const char *kDiffuseRoom = R"(
render: { resolution: [48, 32], seed: 5, max_depth: 8 }
camera: { position: [0, -3.6, 1], look_at: [0, 0, 0.9], up: [0, 0, 1], fov: 50 }
materials:
  white: { type: diffuse, albedo: [0.75, 0.75, 0.75] }
  red:   { type: diffuse, albedo: [0.6, 0.1, 0.1] }
  lamp:  { type: diffuse, albedo: [0, 0, 0] }
objects:
  - { shape: rectangle, size: [3, 3], material: white }
  - { shape: rectangle, size: [3, 3], material: white, transform: { rotate: [180, 0, 0], translate: [0, 0, 2] } }
  - { shape: rectangle, size: [3, 2], material: red, transform: { rotate: [90, 0, 0], translate: [0, 1.5, 1] } }
  - { shape: box, size: [0.6, 0.6, 0.8], material: white, transform: { translate: [0.3, 0.2, 0.4] } }
  - { shape: rectangle, size: [0.5, 0.5], material: lamp, emission: { radiance: [20, 20, 20] },
      transform: { rotate: [180, 0, 0], translate: [0, 0, 1.99] } }
lights:
  - { type: point, position: [-0.8, -0.5, 1.5], intensity: [2, 2, 2] }
)";

TEST(CausticsRender, OffIsThePathTracerBitForBit) {
  SceneRenderer r;
  const std::string scene = sphere_scene(kAreaLight);
  RenderRequest off = request("nimbus.caustics", 4, 9);
  off.options = {{"caustics", "off"}};
  const auto a = r.render(scene, off);
  const auto b = r.render(scene, request("nimbus.pt", 4, 9));
  ASSERT_EQ(a.layers.at("beauty").data, b.layers.at("beauty").data);
  EXPECT_EQ(stat(a, "caustics_photon_paths"), -1.0);  // never armed: not even the statistic
}

// Zero-cost rule: without a sharp material the host reports no sharp object, no photon is ever traced
// (not even a probe), and every camera pass is nimbus.pt's.
TEST(CausticsRender, CausticFreeSceneIsThePathTracer) {
  SceneRenderer r;
  const auto a = r.render(kDiffuseRoom, request("nimbus.caustics", 12, 4));
  const auto b = r.render(kDiffuseRoom, request("nimbus.pt", 12, 4));
  EXPECT_EQ(stat(a, "caustics_photon_paths"), 0.0);
  EXPECT_EQ(stat(a, "caustics_photons"), 0.0);
  EXPECT_EQ(stat(a, "caustics_map_iterations"), 0.0);
  ASSERT_EQ(a.layers.at("beauty").data, b.layers.at("beauty").data);
}

// Photon passes (per-path random numbers, per-task buffers in task order, kd-tree built on disjoint
// subtrees), the schedule, the photons splatted to the lens and the light paths' connections to it
// (summed per pixel in a fixed order) do not depend on threads: the same image with 1 and 3 threads.
TEST(CausticsRender, SameImageAtAnyThreadCount) {
  SceneRenderer r;
  const std::string scene = sphere_scene(kAreaLight);
  RenderRequest one = request("nimbus.caustics", 24, 8), three = one;
  one.threads = 1;
  three.threads = 3;
  const auto a = r.render(scene, one), b = r.render(scene, three);
  EXPECT_GT(stat(a, "caustics_photons"), 0.0);
  EXPECT_GT(stat(a, "caustics_splats"), 0.0);
  EXPECT_GT(stat(a, "caustics_light_splats"), 0.0);
  EXPECT_EQ(stat(a, "caustics_photon_paths"), stat(b, "caustics_photon_paths"));
  ASSERT_EQ(a.layers.at("beauty").data, b.layers.at("beauty").data);
}

double max_rel_diff(const std::vector<float> &beauty, const std::vector<const std::vector<float> *> &parts) {
  double worst = 0;
  for (size_t i = 0; i < beauty.size(); ++i) {
    double s = 0;
    for (const auto *p : parts) s += (*p)[i];
    worst = std::max(worst, std::abs(s - beauty[i]) / std::max(std::abs(double(beauty[i])), 1e-3));
  }
  return worst;
}

TEST(CausticsRender, ElementsAndLightMixSumToBeauty) {
  SceneRenderer r;
  const auto img =
      r.render(sphere_scene(kTwoLights),
               request("nimbus.caustics", 24, 2, {"direct", "indirect", "emission", "caustics", "lightmix"}));
  ASSERT_TRUE(img.layers.count("caustics"));
  const auto &L = img.layers;
  const std::vector<float> &beauty = L.at("beauty").data;
  EXPECT_LT(max_rel_diff(beauty, {&L.at("direct").data, &L.at("indirect").data, &L.at("emission").data,
                                  &L.at("caustics").data}),
            1e-5);
  EXPECT_LT(max_rel_diff(beauty, {&L.at("lightmix.warm").data, &L.at("lightmix.cool").data}), 1e-5);
  // The caustics layer is not empty, and both lights contribute caustic light.
  const Rgb c = mean_rgb(L.at("caustics").data);
  EXPECT_GT(luminance(c), 1e-3 * luminance(mean_rgb(beauty)));
  EXPECT_GT(stat(img, "caustics_photons"), 0.0);
  EXPECT_GT(stat(img, "caustics_light_splats"), 0.0);  // light paths' light is sorted alike
  EXPECT_GT(stat(img, "caustics_bytes_per_photon"), 40.0);
  EXPECT_LT(stat(img, "caustics_bytes_per_photon"), 64.0);
}

// The `caustics` element is a class of paths (those with an eligible merge technique), not a record of
// when photon maps were active: with the switch off it holds path tracing's estimate of that light (the
// beauty still bit for bit nimbus.pt's), and its mean agrees with the solver's under an area light,
// where both converge. Means over 4 seeds each; the tolerance is 3 standard errors of their difference.
TEST(CausticsRender, CausticsElementIsAClassOfPaths) {
  SceneRenderer r;
  const std::string scene = sphere_scene(kAreaLight);
  std::vector<double> on, off;
  for (uint64_t seed = 1; seed <= 4; ++seed) {
    RenderRequest q = request("nimbus.caustics", 32, seed, {"direct", "indirect", "emission", "caustics"});
    on.push_back(luminance(mean_rgb(r.render(scene, q).layers.at("caustics").data)));
    q.options = {{"caustics", "off"}};
    const auto img = r.render(scene, q);
    const auto &L = img.layers;
    off.push_back(luminance(mean_rgb(L.at("caustics").data)));
    EXPECT_LT(max_rel_diff(L.at("beauty").data, {&L.at("direct").data, &L.at("indirect").data,
                                                 &L.at("emission").data, &L.at("caustics").data}),
              1e-5);
    if (seed == 1) {
      RenderRequest pt = request("nimbus.pt", 32, seed);
      ASSERT_EQ(L.at("beauty").data, r.render(scene, pt).layers.at("beauty").data);
    }
  }
  const auto [m_on, se_on] = mean_and_se(on);
  const auto [m_off, se_off] = mean_and_se(off);
  std::printf("caustics element mean: solver %.5f (SE %.5f), switch off %.5f (SE %.5f)\n", m_on, se_on, m_off,
              se_off);
  EXPECT_GT(m_off, 0.1 * m_on) << "the switched-off solver puts no light in the caustics element";
  EXPECT_NEAR(m_on, m_off, 3 * std::hypot(se_on, se_off) + 1e-3 * m_on);
}

// Area light: path tracing converges on the caustic too, so the difference between solver and PT
// renders shrinks with iterations (like their noise), and caustic means agree.
TEST(CausticsRender, AgreesWithPathTracer) { agrees_with_path_tracer(sphere_scene(kAreaLight)); }

// Point light: PT cannot render the caustic at all.
TEST(CausticsRender, ConvergesToLightTracerPointLight) {
  converges_to_light_tracer(R"(
lights:
  - { type: point, position: [-2.0, 0, 1.6], intensity: [12, 12, 12], group: key }
)");
}

// Guided passes run a fixed number of chains seeded by (seed, pass, chain), so the image does not depend
// on the threads; without a guide bound, guided emission is uniform emission, bit for bit.
TEST(CausticsRender, GuidedSameImageAtAnyThreadCountAndUniformWithoutGuide) {
  SceneRenderer r;
  // 320 x 180: passes of a few hundred paths per chain (in smaller ones the chains' start-up draws take
  // the whole budget and guided passes are uniform ones).
  const std::string scene = sphere_scene(kAreaLight, 320, 180);
  RenderRequest one = request("nimbus.caustics", 24, 8), three = one;
  one.options = three.options = {{"photon_emission", "guided"}};
  one.threads = 1;
  three.threads = 3;
  const auto a = r.render(scene, one), b = r.render(scene, three);
  EXPECT_GT(stat(a, "caustics_guided_passes"), 0.0);
  EXPECT_GT(stat(a, "caustics_importance_cells"), 0.0);
  ASSERT_EQ(a.layers.at("beauty").data, b.layers.at("beauty").data);

  RenderRequest unbound = one, uniform = request("nimbus.caustics", 24, 8);
  unbound.guide = "none";
  const auto c = r.render(scene, unbound), d = r.render(scene, uniform);
  EXPECT_EQ(stat(c, "caustics_guided_passes"), 0.0);
  ASSERT_EQ(c.layers.at("beauty").data, d.layers.at("beauty").data);
  EXPECT_NE(c.layers.at("beauty").data, a.layers.at("beauty").data);
}

}  // namespace render_test
}  // namespace nimbus::testing
