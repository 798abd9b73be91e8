// Radius schedule and photon-pass scheduling (solver spec 3.5, 5, 9).
#include <gtest/gtest.h>

#include <cmath>

#include "schedule.hpp"

namespace nimbus::caustics {
namespace schedule_test {

TEST(CausticsSchedule, RadiusStartsAtOneAndAHalfPixelsAndShrinks) {
  const float theta = 1e-3f, ell = 4.0f;
  EXPECT_FLOAT_EQ(merge_radius(theta, ell, 1, 10), 1.5f * theta * ell);
  for (uint32_t j = 1; j < 1000; ++j) {
    const float r0 = merge_radius(theta, ell, j, 10), r1 = merge_radius(theta, ell, j + 1, 10);
    EXPECT_LT(r1, r0);
    // r^2 ~ j^(alpha - 1): the closed form of r_{j+1}^2 = r_j^2 (j + alpha) / (j + 1), up to O(1/j^2).
    EXPECT_NEAR(r1 * r1 / (r0 * r0), (j + kRadiusAlpha) / (j + 1.0f), 0.1f / (float(j) * float(j)) + 1e-6f);
    EXPECT_NEAR(r0, 1.5f * theta * ell * std::pow(float(j), -0.125f), 1e-6f * r0);
  }
  // Consistent but slow: after 10^4 passes the radius is still ~ 1/3 of the first one.
  EXPECT_NEAR(merge_radius(theta, ell, 10000, 10) / merge_radius(theta, ell, 1, 10), std::pow(1e4f, -0.125f),
              1e-5f);
  // Lower clamp: 1e-6 of the scene radius.
  EXPECT_FLOAT_EQ(merge_radius(theta, 0.0f, 1, 10), 1e-5f);
  // Proportional to the path length to the first rough vertex (the pixel footprint there).
  EXPECT_FLOAT_EQ(merge_radius(theta, 2 * ell, 7, 10), 2 * merge_radius(theta, ell, 7, 10));
}

ScheduleConfig config(uint64_t camera_paths) {
  ScheduleConfig c;
  c.camera_paths = camera_paths;
  return c;
}

EfficiencySample sample(double v_merge, double v_camera, double rho, double camera_work, double photon_work) {
  return {v_merge, v_camera, rho, camera_work, photon_work};
}

// rho* = sqrt(V_m1 c_c / (V_c c_p)) minimises (c_c + rho c_p)(V_c + V_m1 / rho): checked against a scan
// of that product, and 0 while anything is unmeasured.
TEST(CausticsSchedule, OptimalRatioMinimisesErrorTimesCost) {
  for (const auto &e :
       {sample(0.02, 0.01, 0.5, 40, 12), sample(1e-4, 0.3, 0.1, 60, 8), sample(0.3, 0.1, 2, 30, 30)}) {
    const double r = optimal_photon_ratio(e), vm1 = e.v_merge * e.rho;
    const auto cost = [&](double rho) {
      return (e.camera_work + rho * e.photon_work) * (e.v_camera + vm1 / rho);
    };
    ASSERT_GT(r, 0);
    for (double f : {0.5, 0.8, 0.95, 1.05, 1.25, 2.0}) EXPECT_GT(cost(r * f), cost(r)) << "factor " << f;
  }
  EXPECT_EQ(optimal_photon_ratio(sample(0, 0.01, 0.5, 40, 12)), 0);  // no merge variance: unmeasured
  EXPECT_EQ(optimal_photon_ratio(sample(0.02, 0.01, 0.5, 40, 0)), 0);
  // The guard: photon work at most kMaxPhotonWorkRatio times the camera paths' (here 3 x 40 / 12 = 10).
  EXPECT_DOUBLE_EQ(optimal_photon_ratio(sample(100, 1e-6, 0.5, 40, 12)), 10.0);
  EXPECT_DOUBLE_EQ(optimal_photon_ratio(sample(100, 0, 0.5, 40, 12)), 10.0);  // merges carry everything
}

// The probe first; then N = clamp(2 rho* N_cam, N_min, N_max) for maps that serve two iterations each,
// with rho* smoothed in log space over passes.
TEST(CausticsSchedule, ProbeThenTheEfficientBudget) {
  PhotonSchedule s(config(200000));
  EXPECT_EQ(s.plan(1), 1u << 16);  // the probe
  s.pass_done(1, 1 << 16, 500);
  EXPECT_TRUE(s.map_active());
  EXPECT_EQ(s.next_pass(), 3u);  // every map serves at least two iterations
  EXPECT_NEAR(s.map_photon_ratio(), 65536.0 / (2 * 200000), 1e-12);
  // Measured: merges carry as much variance as the rest, camera paths cost 4x a photon path, at the
  // probe's ratio: rho* = sqrt(0.16384 * 4) = 0.81.
  const EfficiencySample e = sample(0.01, 0.01, s.map_photon_ratio(), 40, 10);
  s.iteration_done(1, 0.2, e);
  const double rho = optimal_photon_ratio(e);
  EXPECT_NEAR(s.photon_ratio(), rho, 1e-12);
  EXPECT_EQ(s.plan(2), 0u);
  EXPECT_EQ(s.plan(3), uint64_t(std::round(rho * 2 * 200000)));
  s.pass_done(3, s.plan(3), 1000);
  EXPECT_EQ(s.next_pass(), 5u);
  EXPECT_NEAR(s.map_photon_ratio(), rho, 1e-5);
  // The next measurement is smoothed with the first: the geometric mean.
  const EfficiencySample e2 = sample(0.001, 0.01, s.map_photon_ratio(), 40, 10);
  s.iteration_done(3, 0.2, e2);
  EXPECT_NEAR(s.photon_ratio(), std::sqrt(rho * optimal_photon_ratio(e2)), 1e-9);
  // Clamped to [N_min, N_max].
  for (int i = 0; i < 60; ++i) s.iteration_done(4, 0.2, sample(1e-12, 1, 1, 1, 1e6));
  EXPECT_EQ(s.plan(5), 1u << 10);
  for (int i = 0; i < 60; ++i) s.iteration_done(4, 0.2, sample(1e6, 1e-6, 1, 1e6, 1));
  EXPECT_EQ(s.plan(5), 1u << 22);  // rho = 3e6 (the guard): N_max
}

// A pass larger than the budget asks for (the probe of a small image, the N_min floor under a small rho)
// serves several camera passes, so that photon paths per camera path stay near rho.
TEST(CausticsSchedule, LargePassesServeSeveralIterations) {
  PhotonSchedule s(config(4096));  // a small image: 4096 camera paths per iteration
  s.pass_done(1, 1 << 16, 100);    // probe: 65536 paths at rho 0.5 = 32 camera passes
  EXPECT_EQ(s.next_pass(), 33u);
  EXPECT_NEAR(s.map_photon_ratio(), 0.5, 1e-12);
  for (uint64_t i = 1; i < 33; ++i) EXPECT_EQ(s.plan(i + 1), i + 1 < 33 ? 0u : 4096u) << i;
  s.pass_done(33, 1 << 14, 100);  // 16384 paths = 8 camera passes at rho 0.5
  EXPECT_EQ(s.next_pass(), 41u);
}

TEST(CausticsSchedule, BackOffWhenUseless) {
  PhotonSchedule s(config(100000));
  s.pass_done(1, 1 << 16, 0);  // nothing stored
  EXPECT_FALSE(s.map_active());
  EXPECT_EQ(s.idle_level(), 1u);
  EXPECT_EQ(s.plan(2), 0u);
  EXPECT_EQ(s.plan(3), 1u << 10);  // after 2^1 iterations without photons, N_min
  s.pass_done(3, 1 << 14, 5);      // photons, but no useful pixel
  s.iteration_done(3, 0.0, EfficiencySample{});
  EXPECT_FALSE(s.map_active());
  EXPECT_EQ(s.idle_level(), 2u);
  EXPECT_EQ(s.next_pass(), 3u + 1 + 4);
  // Idle levels saturate at 8: one N_min pass per 256 iterations.
  uint64_t it = s.next_pass();
  for (int n = 0; n < 20; ++n) {
    EXPECT_GT(s.plan(it), 0u);
    s.pass_done(it, s.plan(it), 0);
    it = s.next_pass();
  }
  EXPECT_EQ(s.idle_level(), kMaxIdleLevel);
  const uint64_t before = it;
  s.pass_done(it, 1, 0);
  EXPECT_EQ(s.next_pass(), before + 256);
  // Any useful pixel resets the idle level.
  s.pass_done(s.next_pass(), 1 << 14, 100);
  s.iteration_done(s.next_pass(), 0.01, EfficiencySample{});
  EXPECT_EQ(s.idle_level(), 0u);
  EXPECT_TRUE(s.map_active());
}

}  // namespace schedule_test
}  // namespace nimbus::caustics
