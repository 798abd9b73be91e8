// The power a light's photons carry, which light selection for photons weighs (emitters.hpp): the share
// of its power sent towards the sharp objects, and what that does to the prism scene's selection.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <nimbus/cpp/emitter_selection.hpp>

#include "emitter_stubs.hpp"
#include "emitters.hpp"

namespace nimbus::caustics {
namespace photon_share_test {

using stubs::kStubLights;
using stubs::three_lights;
using stubs::two_targets;
// A finite light's photons carry the power it sends towards the targets, which is what light selection
// weighs: a point light's power times the targets' share of its sphere of directions, a spot's times
// their share of its cone, an area light's times their share of its hemisphere; a spot turned away from
// every target none (its photons end at their first, rough, vertex); a light inside a target all of it.
// A bright point light seeing a small target must not outweigh a weaker spot aimed straight at it. The
// shares are of the objects' own spheres when the targets list them, else of the clusters'.
TEST(CausticsPhotonShare, PhotonPowerIsThePowerSentTowardsTheTargets) {
  const auto solid_angle = [](const Vec3f &from, const Sphere &s) {
    return 2 * kPi * (1 - std::sqrt(1 - sqr(s.radius) / length_squared(s.center - from)));
  };
  const SharpTargets targets = two_targets();
  std::vector<Emitter> lights = three_lights();
  EmitterSet set;
  set.build(lights, Vec3f(0, 0, 0), 10, nullptr, &kStubLights, targets);
  const Sphere &ball = targets.clusters[0].sphere, &side = targets.clusters[1].sphere;
  ASSERT_LT(ball.radius, 0.6f);  // the ball's cluster is the ball
  const std::vector<double> &power = set.photon_powers();
  const float point_share =
      (solid_angle(lights[0].position, ball) + solid_angle(lights[0].position, side)) / (4 * kPi);
  EXPECT_NEAR(power[0], 2 * point_share, 1e-4 * power[0]);
  const float spot_cone = 2 * kPi * (1 - std::cos(0.5f));
  EXPECT_NEAR(power[1], 1 * solid_angle(lights[1].position, ball) / spot_cone, 1e-4 * power[1]);
  const float area_share =
      (solid_angle(lights[2].position, ball) + solid_angle(lights[2].position, side)) / (2 * kPi);
  EXPECT_NEAR(power[2], area_share, 1e-4 * power[2]);

  lights[1].axis = Vec3f(0, 0, 1);   // the spot turned up, away from both targets
  lights[2].position = ball.center;  // the area light inside the ball's sphere
  lights[0].power = 1e4f;            // far brighter than the spot, but it sees the targets small
  lights.push_back(three_lights()[1]);
  set.build(lights, Vec3f(0, 0, 0), 10, nullptr, &kStubLights, targets);
  EXPECT_EQ(set.photon_powers()[1], 0.0);
  EXPECT_NEAR(set.photon_powers()[2], 1.0, 1e-6);
  EXPECT_LT(set.photon_powers()[0], 1e4 * 0.02);
  EXPECT_GT(set.photon_powers()[3], 0.15);  // the spot aimed at the ball keeps its share of power

  // With the objects listed, a lamp inside a cluster's sphere, between its two small balls, sends them
  // only the balls' solid angles, not its whole power.
  SharpTargets pair;
  pair.objects = {{Vec3f(-1, 0, 0), 0.1f}, {Vec3f(1, 0, 0), 0.1f}};
  std::vector<Target> balls = {{pair.objects[0], Vec3f(-1.1f, -0.1f, -0.1f), Vec3f(-0.9f, 0.1f, 0.1f)},
                               {pair.objects[1], Vec3f(0.9f, -0.1f, -0.1f), Vec3f(1.1f, 0.1f, 0.1f)}};
  cluster(balls, 1, pair.clusters);
  pair.all = enclose(pair.clusters);
  ASSERT_EQ(pair.clusters.size(), 1u);
  std::vector<Emitter> lamp(1, three_lights()[0]);
  lamp[0].position = Vec3f(0, 0, 0);
  set.build(lamp, Vec3f(0, 0, 0), 10, nullptr, &kStubLights, pair);
  EXPECT_TRUE(set[0].aims.empty()) << "the lamp is inside the cluster's sphere";
  const float balls_share = 2 * solid_angle(lamp[0].position, pair.objects[0]) / (4 * kPi);
  EXPECT_NEAR(set.photon_powers()[0], 2 * balls_share, 1e-4 * 2 * balls_share);
}

// The prism scene's lights (scenes/caustics/prism.yaml): a 40 W/sr spot whose narrow cone lies inside the
// glass's sphere, and a 2.5 W/sr fill lamp nearer the camera that sees the glass small. Selected by the
// kit's rule (photon power over squared camera distance, the defensive share by whole power), the spot
// must keep a fair share of the photon paths: weighed by its whole power, the fill took 99.9 % and the
// rainbow was a few fireflies.
TEST(CausticsPhotonShare, KeySpotOnGlassIsNotStarvedByABrightFillLamp) {
  SharpTargets prism;
  prism.objects = {{Vec3f(0, 0, 0.85f), 0.33f}};
  std::vector<Target> objects = {{prism.objects[0], Vec3f(-0.1f, -0.3f, 0.8f), Vec3f(0.1f, 0.3f, 0.97f)}};
  cluster(objects, kMaxTargets, prism.clusters);
  prism.all = enclose(prism.clusters);
  const float half_angle = 3 * kPi / 180;
  std::vector<Emitter> lights(2);
  lights[0].kind = EmitterKind::Spot, lights[0].flags = NIMBUS_LIGHT_DELTA_POSITION;
  lights[0].position = Vec3f(-0.907f, 0, 0.371f), lights[0].axis = normalize(Vec3f(0.857f, 0, 0.515f));
  lights[0].cos_theta_e = std::cos(half_angle), lights[0].power = 40 * 2 * kPi * (1 - std::cos(half_angle));
  lights[1].kind = EmitterKind::Point, lights[1].flags = NIMBUS_LIGHT_DELTA_POSITION;
  lights[1].position = Vec3f(1, -2, 2.5f), lights[1].power = 2.5f * 4 * kPi;
  EmitterSet set;
  set.build(lights, Vec3f(0, 0, 1), 6, nullptr, &kStubLights, prism);
  const Vec3f camera(0.7f, -2.3f, 1.5f);
  std::vector<sdk::EmitterSelection::Light> in(2);
  for (int l = 0; l < 2; ++l)
    in[l] = {set.photon_powers()[l], false, double(length_squared(lights[l].position - camera)), 0,
             lights[l].power};
  const std::vector<double> p = sdk::EmitterSelection::probabilities(in, nullptr, nullptr, false);
  EXPECT_NEAR(set.photon_powers()[0], lights[0].power, 1e-6 * lights[0].power)
      << "all of it enters the glass";
  EXPECT_GT(p[0], 0.1) << "spot's share of the photon paths (all of it weighed by whole power: ~0.001)";
}

}  // namespace photon_share_test
}  // namespace nimbus::caustics
