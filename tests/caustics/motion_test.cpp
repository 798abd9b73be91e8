// Motion blur in the caustics solver (spec 7.1): photons carry a scene time when geometry or lights move
// and lookups merge only photons of similar time. A caustic of a moving point light, or of a moving glass
// ball under a point light, converges to an independent light tracer that gives each light path its own
// time (only the two of them render point-light caustics); under an area light the solver agrees with
// nimbus.pt. A shutter over a still scene, or a camera that alone moves, leaves photons untimed.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include "photon_windows.hpp"
#include "sphere_scenes.hpp"

namespace nimbus::testing {
namespace motion_test {

const char *kShutter = ", shutter: { close: 1 }";
const char *kPointLight = R"(
lights:
  - { type: point, position: [-2.0, 0, 1.6], intensity: [12, 12, 12], group: key }
)";

TEST(CausticsMotion, MovingPointLightConvergesToLightTracer) {
  converges_to_light_tracer_in(from_above(R"(
lights:
  - { type: point, position: [-2.0, 0, 1.6], intensity: [12, 12, 12], group: key,
      motion: [{ time: 0, translate: [0, -0.5, 0] }, { time: 1, translate: [0, 0.5, 0] }] }
)",
                                          1, kShutter));
}

TEST(CausticsMotion, MovingGlassConvergesToLightTracer) {
  converges_to_light_tracer_in(from_above(
      kPointLight, 1, kShutter,
      ", motion: [{ time: 0, translate: [-0.15, -0.3, 0] }, { time: 1, translate: [0.15, 0.3, 0] }]"));
}

// Under an area light path tracing converges on the moving ball's caustic too (agrees_with_path_tracer).
TEST(CausticsMotion, MovingGlassAgreesWithPathTracer) {
  agrees_with_path_tracer(sphere_scene(
      R"(
  - { shape: rectangle, size: [0.35, 0.35], material: lamp, emission: { radiance: [110, 110, 110] },
      transform: { rotate: [180, 0, 0], translate: [-1.4, 0, 1.9] } }
)",
      80, 45,
      "{ position: [1.6, -1.8, 2.4], look_at: [0.5, 0.05, 0.05], up: [0, 0, 1], fov: 36, shutter: { close: 1 "
      "} }",
      ", motion: [{ time: 0, translate: [0, -0.3, 0] }, { time: 1, translate: [0, 0.3, 0.2] }]"));
}

// A plate above the floor hides part of a moving light's caustic from the camera for the first half of
// the shutter, then slides away: the lookups behind it must merge only photons of their own time (a
// lookup merging every time there lights the hidden half of the exposure with the caustic as it was
// then: the region means come out ~6 % low). The region means over the caustic and over its hidden part
// match the light tracer within 3 sigma (Student's t for the solver's sample standard error over
// kSeeds renders, 7 degrees of freedom: 4.53 SEs).
TEST(CausticsMotion, CausticHiddenByAMovingPlateConvergesToLightTracer) {
  const std::string scene = from_above(
      R"(
lights:
  - { type: point, position: [-2.0, 0, 1.6], intensity: [12, 12, 12], group: key,
      motion: [{ time: 0, translate: [0, -0.5, 0] }, { time: 1, translate: [0, 0.5, 0] }] }
)",
      1, kShutter,
      R"( }
  - { shape: box, size: [0.2, 0.2, 0.01], material: floor,
      motion: [{ time: 0, translate: [0.71, -0.9, 2.4] }, { time: 0.5, translate: [0.71, -0.9, 2.4] },
               { time: 0.55, translate: [3.71, -0.9, 2.4] }, { time: 1, translate: [3.71, -0.9, 2.4] }])");
  constexpr int kSeeds = 8, kReferenceSeeds = 4;
  constexpr double kT7 = 4.53;
  const Region regions[2] = {{40, 14, 60, 32}, {42, 22, 56, 32}};  // the caustic; its hidden part
  SceneRenderer r;
  std::vector<double> solver_means[2], lt_means[2];  // per region, one per render
  for (int k = 0; k < kSeeds; ++k) {
    const ImageLayers solver = r.render(scene, request("nimbus.caustics", 64, 40 + k));
    for (int g = 0; g < 2; ++g) solver_means[g].push_back(region_mean(solver, regions[g]));
    if (k >= kReferenceSeeds) continue;
    const ImageLayers lt = r.render(scene, request("nimbus.lt", 1024, 60 + k));
    for (int g = 0; g < 2; ++g) lt_means[g].push_back(region_mean(lt, regions[g]));
  }
  for (int g = 0; g < 2; ++g) {
    const auto [mean, se] = mean_and_se(solver_means[g]);
    const auto [lt_mean, lt_se] = mean_and_se(lt_means[g]);
    const double combined = std::sqrt(se * se + lt_se * lt_se);
    std::printf("region %d: solver %.5f, light tracer %.5f, combined SE %.5f (%.2f %%): %.2f SEs\n", g, mean,
                lt_mean, combined, 100 * combined / lt_mean, (mean - lt_mean) / combined);
    EXPECT_NEAR(mean, lt_mean, kT7 * combined) << "region " << g;
    // The test must be able to see the bias of merging every time: 6 % of the mean.
    EXPECT_LT(kT7 * combined, 0.04 * lt_mean) << "region " << g;
  }
}

// Zero cost: a shutter over a scene in which nothing moves draws no time anywhere.
TEST(CausticsMotion, StillSceneWithAShutterRendersBitForBitAsWithout) {
  SceneRenderer r;
  const auto plain = r.render(from_above(kPointLight), request("nimbus.caustics", 6, 7));
  const auto shuttered = r.render(from_above(kPointLight, 1, kShutter), request("nimbus.caustics", 6, 7));
  EXPECT_GT(stat(plain, "caustics_photon_paths"), 0.0);
  EXPECT_EQ(plain.layers.at("beauty").data, shuttered.layers.at("beauty").data);
}

// Photons live in world space: a moving camera alone needs no photon times; moving geometry or lights do.
TEST(CausticsMotion, OnlyMovingGeometryOrLightsTimePhotons) {
  static uint32_t moving = 0;
  nimbus_host_camera_v1_t camera{};
  camera.struct_size = sizeof(camera);
  camera.shutter = [](const nimbus_host_t *, float *open, float *close) {
    *open = 0, *close = 2;
    return moving;
  };
  camera.connect_at = [](const nimbus_host_t *, const float *, float, const float *, float *, float *) {
    return 0.0f;
  };
  for (uint32_t m : {0u, NIMBUS_MOTION_CAMERA, NIMBUS_MOTION_GEOMETRY, NIMBUS_MOTION_LIGHTS,
                     NIMBUS_MOTION_CAMERA | NIMBUS_MOTION_LIGHTS}) {
    moving = m;
    const caustics::PhotonClock clock = caustics::PhotonClock::of(nullptr, &camera);
    EXPECT_EQ(clock.timed(), (m & (NIMBUS_MOTION_GEOMETRY | NIMBUS_MOTION_LIGHTS)) != 0)
        << "motion bits " << m;
  }
  // The window in shutter coordinates: 2h wide around u_c with the factor 1/(2h), mirrored in the shutter's
  // ends, so that a photon near an end counts for camera paths on both sides of it.
  moving = NIMBUS_MOTION_GEOMETRY;
  const caustics::PhotonClock clock = caustics::PhotonClock::of(nullptr, &camera);
  EXPECT_FLOAT_EQ(caustics::PhotonClock::half_width(1), 0.125f);
  EXPECT_LT(caustics::PhotonClock::half_width(100), caustics::PhotonClock::half_width(1))
      << "the window shrinks like the radius";
  const caustics::TimeWindow w = clock.window(0.05f, 0.1f);
  EXPECT_FLOAT_EQ(w.rho, 0.2f);
  EXPECT_FLOAT_EQ(w.weight(0.1f), 5.0f);
  EXPECT_FLOAT_EQ(w.weight(0.02f), 10.0f) << "direct and mirrored in u = 0";
  EXPECT_FLOAT_EQ(w.weight(0.2f), 0.0f);
  // Symmetric, and integrating to 1 over u_c for every u_p: the shutter's average is exact.
  for (float up : {0.0f, 0.03f, 0.5f, 0.97f}) {
    double integral = 0;
    constexpr int kSteps = 100000;
    for (int i = 0; i < kSteps; ++i) integral += clock.window((i + 0.5f) / kSteps, 0.1f).weight(up) / kSteps;
    EXPECT_NEAR(integral, 1.0, 1e-3) << "u_p " << up;
  }
}

}  // namespace motion_test
}  // namespace nimbus::testing
