// --target-error estimates relMSE from the odd and even halves of the iterations, without a reference.
// Against a long reference, the error actually achieved lies within a factor 2 of the target.
#include <gtest/gtest.h>

#include <cstdio>

#include "support/render_support.hpp"

namespace nimbus::testing {
namespace target_error_test {

const char *kScene = R"(
render: { resolution: [32, 32], seed: 3, max_depth: 6 }
camera: { position: [0, -3.9, 1], look_at: [0, 0, 1], up: [0, 0, 1], fov: 39 }
materials:
  white: { type: diffuse, albedo: [0.75, 0.75, 0.75] }
  red:   { type: diffuse, albedo: [0.63, 0.065, 0.05] }
  lamp:  { type: diffuse, albedo: [0, 0, 0] }
objects:
  - { shape: rectangle, size: [2, 2], material: white }
  - { shape: rectangle, size: [2, 2], material: white, transform: { rotate: [90, 0, 0], translate: [0, 1, 1] } }
  - { shape: rectangle, size: [2, 2], material: red, transform: { rotate: [0, 90, 0], translate: [-1, 0, 1] } }
  - { shape: sphere, center: [0.3, 0, 0.4], radius: 0.4, material: white }
  - { shape: rectangle, size: [0.6, 0.6], material: lamp, emission: { radiance: [17, 15, 12] },
      transform: { rotate: [180, 0, 0], translate: [0, 0, 1.99] } }
)";

// A nimbus.pt render of `iterations` (0: the stopping rule decides) with `seed`.
RenderRequest pt_request(uint64_t iterations, uint64_t seed) {
  RenderRequest r;
  r.integrator = "nimbus.pt";
  r.iterations = iterations;
  r.seed = seed;
  return r;
}

TEST(TargetError, AchievedErrorIsWithinFactorTwoOfTarget) {
  SceneRenderer r;
  const auto ref = r.render(kScene, pt_request(8192, 99));
  for (const double target : {0.02, 0.005}) {
    RenderRequest req = pt_request(0, 7);
    req.target_error = target;
    const auto img = r.render(kScene, req);
    ASSERT_EQ(img.strings.at("nimbus:stopped_by"), "target_error");
    const double estimated = img.numbers.at("nimbus:estimated_relmse");
    const double achieved = rel_mse(img.layers.at("beauty").data, ref.layers.at("beauty").data);
    std::printf("target %.4g: %g iterations, estimated %.4g, achieved %.4g\n", target,
                img.numbers.at("nimbus:iterations"), estimated, achieved);
    EXPECT_LT(estimated, target);
    EXPECT_GT(achieved, target / 2);
    EXPECT_LT(achieved, target * 2);
  }
}

// The scene's render.target_error does what --target-error does (with no iteration limit of its own).
TEST(TargetError, SceneKeyStopsAtTheTarget) {
  SceneRenderer r;
  std::string scene = kScene;
  scene.replace(scene.find("seed: 3"), 7, "seed: 3, target_error: 0.02");
  RenderRequest req = pt_request(0, 7);
  const auto img = r.render(scene, req);
  ASSERT_EQ(img.strings.at("nimbus:stopped_by"), "target_error");
  EXPECT_LT(img.numbers.at("nimbus:estimated_relmse"), 0.02);
  EXPECT_DOUBLE_EQ(img.numbers.at("nimbus:target_error"), 0.02);
}

TEST(TargetError, NoHalfBuffersWithoutATarget) {
  SceneRenderer r;
  const auto img = r.render(kScene, pt_request(4, 7));
  EXPECT_EQ(img.numbers.count("nimbus:estimated_relmse"), 0u);
  EXPECT_EQ(img.strings.at("nimbus:stopped_by"), "iterations");
}

}  // namespace target_error_test
}  // namespace nimbus::testing
