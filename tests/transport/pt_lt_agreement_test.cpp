// Path tracing and light tracing share only the host's BSDFs, lights and camera; on a diffuse Cornell
// box both are consistent, so their difference must shrink like their noise: relMSE between the two
// renders falls as 1/iterations, and their image means agree within a few standard errors.
#include <gtest/gtest.h>

#include <cstdio>

#include "support/render_support.hpp"

namespace nimbus::testing {
namespace pt_lt_agreement_test {

const char *kDiffuseCornell = R"(
render: { resolution: [24, 24], seed: 3, max_depth: 6 }
camera: { position: [0, -3.9, 1], look_at: [0, 0, 1], up: [0, 0, 1], fov: 39 }
materials:
  white: { type: diffuse, albedo: [0.75, 0.75, 0.75] }
  red:   { type: diffuse, albedo: [0.63, 0.065, 0.05] }
  green: { type: diffuse, albedo: [0.14, 0.45, 0.091] }
  lamp:  { type: diffuse, albedo: [0, 0, 0] }
objects:
  - { shape: rectangle, size: [2, 2], material: white }
  - { shape: rectangle, size: [2, 2], material: white, transform: { rotate: [180, 0, 0], translate: [0, 0, 2] } }
  - { shape: rectangle, size: [2, 2], material: white, transform: { rotate: [90, 0, 0], translate: [0, 1, 1] } }
  - { shape: rectangle, size: [2, 2], material: red, transform: { rotate: [0, 90, 0], translate: [-1, 0, 1] } }
  - { shape: rectangle, size: [2, 2], material: green, transform: { rotate: [0, -90, 0], translate: [1, 0, 1] } }
  - { shape: sphere, center: [-0.4, 0, 0.4], radius: 0.4, material: white }
  - { shape: rectangle, size: [0.6, 0.6], material: lamp, emission: { radiance: [17, 15, 12] },
      transform: { rotate: [180, 0, 0], translate: [0, 0, 1.99] } }
)";

RenderRequest request(const std::string &integrator, uint64_t iterations, uint64_t seed) {
  RenderRequest req;
  req.integrator = integrator, req.iterations = iterations, req.seed = seed;
  return req;
}

TEST(PtLtAgreement, DifferenceFallsAsOneOverIterations) {
  SceneRenderer r;
  const uint64_t n = 64;
  const auto pt1 = r.render(kDiffuseCornell, request("nimbus.pt", n, 11));
  const auto lt1 = r.render(kDiffuseCornell, request("nimbus.lt", n, 12));
  const auto pt4 = r.render(kDiffuseCornell, request("nimbus.pt", 8 * n, 13));
  const auto lt4 = r.render(kDiffuseCornell, request("nimbus.lt", 8 * n, 14));
  const double e1 = rel_mse(pt1.layers.at("beauty").data, lt1.layers.at("beauty").data);
  const double e8 = rel_mse(pt4.layers.at("beauty").data, lt4.layers.at("beauty").data);
  std::printf("relMSE(pt, lt): %.3g at %llu iterations, %.3g at %llu (ratio %.2f)\n", e1,
              (unsigned long long)n, e8, (unsigned long long)(8 * n), e1 / e8);
  // Unbiased estimators: 8x the samples gives 1/8 the squared difference (allow noise: at least 4x).
  // A bias between the two would make the ratio tend to 1.
  EXPECT_GT(e1 / e8, 4.0) << "relMSE " << e1 << " at " << n << " iterations, " << e8 << " at " << 8 * n;

  // Image means: with 8n iterations the mean's relative noise is far below 1 %.
  const Rgb mpt = mean_rgb(pt4.layers.at("beauty").data), mlt = mean_rgb(lt4.layers.at("beauty").data);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(mpt[c] / mlt[c], 1.0, 0.01) << "channel " << c;
}

}  // namespace pt_lt_agreement_test
}  // namespace nimbus::testing
