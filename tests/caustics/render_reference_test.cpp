// Longer statistical renders with nimbus.caustics (label `long`: CI's sanitizer pass leaves them out,
// the shorter renders of render_test.cpp run the same code under it): photons from an environment map's hot
// spot against a long nimbus.pt render, and convergence to nimbus.lt under a spot light, a sun, guided
// photon emission and the adaptive emission map; the focus of a point light kept sharp by the per-pixel
// merge radius.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include "lights/environment_map_fixture.hpp"
#include "sphere_scenes.hpp"
#include "support/render_support.hpp"

namespace nimbus::testing {
namespace render_reference_test {

// An environment map with a hot spot (a photographed sky with its sun) and no other light: photons come
// from the hot spot only (environment_emission.hpp). Path tracing converges under a hittable environment
// (slowly: the hot spot's caustic comes as fireflies), so a long nimbus.pt render is the reference: the
// solver's error against it falls with iterations and the image means match. A uniform environment
// emits nothing: not armed, no photon.
TEST(CausticsRender, EnvironmentMapPhotonsAgreeWithPathTracer) {
  const std::string map = write_environment_map("nimbus_caustics_environment.exr");
  SceneRenderer r;
  const std::string scene = sphere_scene("environment: { map: " + map + " }\n");
  const uint64_t n = 16;
  const auto reference = r.render(scene, request("nimbus.pt", 2048, 46));
  const auto s1 = r.render(scene, request("nimbus.caustics", n, 41));
  const auto s1b = r.render(scene, request("nimbus.caustics", n, 42));
  const auto s8 = r.render(scene, request("nimbus.caustics", 8 * n, 43));
  const auto s8b = r.render(scene, request("nimbus.caustics", 8 * n, 48));
  std::filesystem::remove(map);
  EXPECT_GT(stat(s8, "caustics_photon_paths"), 0);
  const std::vector<float> &ref = reference.layers.at("beauty").data;
  // The solver's own error, from two independent renders at each count (the reference's fireflies
  // would set a floor under a comparison with it): its variance falls 8x; 3x leaves room for noise.
  const double e1 = rel_mse(s1.layers.at("beauty").data, s1b.layers.at("beauty").data);
  const double e8 = rel_mse(s8.layers.at("beauty").data, s8b.layers.at("beauty").data);
  std::printf(
      "relMSE between two solver renders under a map: %.4g at %llu iterations, %.4g at %llu (ratio %.2f)\n",
      e1, (unsigned long long)n, e8, (unsigned long long)(8 * n), e1 / e8);
  EXPECT_GT(e1 / e8, 3.0);
  // Image means: the two solver renders differ by ~0.5 % (one SE ~0.3 %); the reference, with its
  // fireflies, by more. 2 % is several of either, far below a missing or doubled caustic (~10 %).
  const double ms = luminance(mean_rgb(s8.layers.at("beauty").data));
  const double ms_b = luminance(mean_rgb(s8b.layers.at("beauty").data));
  const double mp = luminance(mean_rgb(ref));
  std::printf("image mean: solver %.5f, %.5f; pt 2048 %.5f\n", ms, ms_b, mp);
  EXPECT_NEAR(0.5 * (ms + ms_b) / mp, 1.0, 0.02);

  const auto uniform =
      r.render(sphere_scene("environment: { color: [0.5, 0.5, 0.5] }\n"), request("nimbus.caustics", 4, 45));
  EXPECT_EQ(stat(uniform, "caustics_photon_paths"), 0);
}

// Spot light whose cone (40 degrees, soft edge) is wider than the cone towards the sphere: photons are
// aimed at the sphere and carry the spot's falloff in their direction.
TEST(CausticsRender, ConvergesToLightTracerSpot) {
  converges_to_light_tracer(R"(
lights:
  - { type: spot, position: [-2.0, 0, 1.6], direction: [2.0, 0, -1.3], cone: 40, softness: 25,
      intensity: [12, 12, 12], group: key }
)");
}

// Sun (a 6 degree disk): infinite-light emission from the solver's own disk around the sharp surfaces.
TEST(CausticsRender, ConvergesToLightTracerSun) {
  converges_to_light_tracer(R"(
lights:
  - { type: sun, direction: [2.0, 0, -1.0], irradiance: [3, 3, 3], angular_diameter: 6, group: sun }
)");
}

// Metropolis photon guiding (spec 6.3) keeps the estimate unbiased: with the guided passes' mixture
// weights and effective photon counts the region means match the light tracer within the same bounds.
// The error falls less (the chains' correlated photons), so 1.5x. At 160 x 90 pixels, so that passes
// are large enough for the chains to step (in smaller ones their start-up draws take the whole budget).
TEST(CausticsRender, GuidedConvergesToLightTracerPointLight) {
  converges_to_light_tracer(R"(
lights:
  - { type: point, position: [-2.0, 0, 1.6], intensity: [12, 12, 12], group: key }
)",
                            {{"photon_emission", "guided"}}, 1.5, 2);
}

// The adaptive emission map (a point light's cone, a sun's disk around the sphere) keeps the estimate
// unbiased: both sides weigh a photon by the map's density at its emission numbers.
TEST(CausticsRender, AdaptiveEmissionMapConvergesToLightTracer) {
  converges_to_light_tracer(R"(
lights:
  - { type: point, position: [-2.0, 0, 1.6], intensity: [12, 12, 12], group: key }
)",
                            {{"photon_emission", "adaptive-map"}});
  converges_to_light_tracer(R"(
lights:
  - { type: sun, direction: [2.0, 0, -1.0], irradiance: [3, 3, 3], angular_diameter: 6, group: sun }
)",
                            {{"photon_emission", "adaptive-map"}});
}

// The shipped scenes/caustics/NAME.yaml (a Cornell box under a point light with a glass and a mirror
// sphere) at 64 x 64 and a maximum path length of 8.
std::string small_box(const std::string &name) {
  std::ifstream file(std::string(NIMBUS_SOURCE_DIR) + "/scenes/caustics/" + name + ".yaml");
  std::string scene((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  for (const auto &[from, to] :
       {std::pair<std::string, std::string>{"resolution: [512, 512]", "resolution: [64, 64]"},
        {"max_depth: 12", "max_depth: 8"}}) {
    const size_t at = scene.find(from);
    EXPECT_NE(at, std::string::npos) << name << ": " << from;
    if (at != std::string::npos) scene.replace(at, from.size(), to);
  }
  return scene;
}

// In that box the light-path trial keeps light paths (light_path_trial.hpp), and the solver with them
// converges to nimbus.lt, an independent estimator, on the floor in the glass sphere's shadow (lit
// indirectly, below the caustic's focus, whose merge kernel at this resolution moves a few percent of
// its light across any row), on the mirror's caustic on the side wall, and on the back wall. Means
// over 4 solver seeds and 2 light-tracer seeds; the bound is 4 standard errors of their difference,
// from each side's spread over its seeds (Student's t with 3 degrees of freedom leaves 97 % inside it).
void expect_light_paths_converge(const std::string &scene) {
  SceneRenderer r;
  const Region regions[] = {{38, 58, 50, 61}, {58, 53, 62, 58}, {16, 8, 48, 24}};
  const char *names[] = {"floor in the glass sphere's shadow", "side-wall caustic", "back wall"};
  std::vector<ImageLayers> solver, lt;
  for (uint64_t seed : {51, 52, 53, 54}) {
    solver.push_back(r.render(scene, request("nimbus.caustics", 128, seed)));
    EXPECT_EQ(stat(solver.back(), "caustics_light_paths_kept"), 1.0) << "seed " << seed;
  }
  for (uint64_t seed : {55, 56}) lt.push_back(r.render(scene, request("nimbus.lt", 1024, seed)));
  const auto mean_se = [](const std::vector<ImageLayers> &images, const Region &g, double &se) {
    double s = 0, s2 = 0;
    for (const ImageLayers &img : images) {
      const double m = region_mean(img, g);
      s += m, s2 += m * m;
    }
    const double n = double(images.size()), mean = s / n;
    se = std::sqrt(std::max(0.0, (s2 - n * mean * mean) / (n - 1)) / n);
    return mean;
  };
  for (size_t k = 0; k < std::size(regions); ++k) {
    double se_s = 0, se_l = 0;
    const double ms = mean_se(solver, regions[k], se_s), ml = mean_se(lt, regions[k], se_l);
    const double se = std::sqrt(se_s * se_s + se_l * se_l);
    std::printf("%s: solver %.5f (SE %.5f), lt %.5f (SE %.5f): %.2f SE apart, ratio %.4f\n", names[k], ms,
                se_s, ml, se_l, (ms - ml) / se, ms / ml);
    EXPECT_LT(std::abs(ms - ml), 4 * se) << names[k];
  }
}

// Measured 0.67, 0.14 and 0.74 standard errors apart. Light paths without their MIS weights would
// double the floor's indirect light; without light paths the trial's statistic fails.
TEST(CausticsRender, LightPathsInAClosedBoxConvergeToLightTracer) {
  expect_light_paths_converge(small_box("cornell-point"));
}

// The same box with motion blur (scenes/caustics/cornell-moving.yaml): the glass sphere moves 30 cm while
// the shutter is open, so its shadow and caustic sweep the floor. Light paths, photons and camera paths
// each draw their own time; the merges take photons of a window of times around the camera path's, and
// light paths and splats none (light_paths.hpp), which the MIS weights count. Measured 1.18, 0.58 and
// 0.45 standard errors apart; light paths traced at the shutter's opening put the side wall 7.4 apart.
TEST(CausticsRender, LightPathsInAMovingClosedBoxConvergeToLightTracer) {
  expect_light_paths_converge(small_box("cornell-moving"));
}

// The focus of a point light behind a glass sphere (320 x 180, the caustic's core a few pixels wide): a
// kernel of the schedule's radius spreads the focus onto its surroundings, a per-pixel error that the
// region means above do not see (the light is only moved). With the radius per pixel (pixel_radius.hpp)
// the kernel shrinks where the photons crowd. Measured per pixel over the focus (the brightest 0.5 % of
// the light tracer's covered pixels): the squared relative bias, (mean of two solver renders - mean of
// two light-tracer renders)^2 less both means' variances (from each pair's difference), divided by
// (reference^2 + 0.01) as relMSE does, over the 111 focus pixels. Measured at 64 iterations: 0.063
// (SE 0.024) with the schedule's radius alone, 0.0009 (SE 0.0006) with the radius per pixel. The bound
// 0.015 lies 22 standard errors above the latter (the estimate's SE from its spread over the pixels,
// printed) and 2 below the former.
TEST(CausticsRender, FocusOfAPointLightIsNotBlurred) {
  SceneRenderer r;
  const std::string scene =
      from_above("lights:\n  - { type: point, position: [-2.0, 0, 1.6], intensity: 12 }\n", 4);
  const auto lt1 = r.render(scene, request("nimbus.lt", 256, 34)),
             lt2 = r.render(scene, request("nimbus.lt", 256, 35));
  const auto s1 = r.render(scene, request("nimbus.caustics", 64, 31)),
             s2 = r.render(scene, request("nimbus.caustics", 64, 32));
  EXPECT_GT(stat(s1, "caustics_pixel_radius_shrunk"), 0.0);
  const auto lum = [](const ImageLayers &img) {
    const std::vector<float> &d = img.layers.at("beauty").data;
    std::vector<double> v(d.size() / 3);
    for (size_t i = 0; i < v.size(); ++i) v[i] = luminance(Rgb::load(&d[3 * i]));
    return v;
  };
  const std::vector<double> a1 = lum(lt1), a2 = lum(lt2), b1 = lum(s1), b2 = lum(s2);
  std::vector<double> covered;
  for (size_t i = 0; i < a1.size(); ++i)
    if (a1[i] > 0 && a2[i] > 0) covered.push_back(a1[i] + a2[i]);
  std::sort(covered.begin(), covered.end());
  const double threshold = covered[size_t(0.995 * double(covered.size()))];
  double sum = 0, sum2 = 0;
  size_t n = 0;
  for (size_t i = 0; i < a1.size(); ++i) {
    if (!(a1[i] > 0 && a2[i] > 0 && a1[i] + a2[i] >= threshold)) continue;
    const double ref = (a1[i] + a2[i]) / 2, test = (b1[i] + b2[i]) / 2;
    const double var = ((a1[i] - a2[i]) * (a1[i] - a2[i]) + (b1[i] - b2[i]) * (b1[i] - b2[i])) / 4;
    const double bias2 = ((test - ref) * (test - ref) - var) / (ref * ref + 0.01);
    sum += bias2, sum2 += bias2 * bias2, ++n;
  }
  const double mean = sum / double(n), se = std::sqrt((sum2 / double(n) - mean * mean) / double(n - 1));
  std::printf("focus (%zu pixels): squared relative bias %.4g (SE %.2g); shrunk first lookups %.4f\n", n,
              mean, se, stat(s1, "caustics_pixel_radius_shrunk"));
  EXPECT_LT(mean, 0.015);
}

}  // namespace render_reference_test
}  // namespace nimbus::testing
