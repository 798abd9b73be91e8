// Radius schedule and photon-pass scheduling (solver spec 3.5, 5, 9).
#include <gtest/gtest.h>

#include <cmath>

#include "schedule.hpp"

namespace nimbus::caustics {
namespace {

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
  c.n_max = 1 << 20;
  c.photon_paths_per_camera_path = 0;    // no cap: N_min = N_max / 64
  c.min_floor = 1;                       // the schedule's logic, not the floor (tested above)
  c.stored_photons_per_camera_path = 0;  // nor the cap on stored photons (tested below)
  c.probe = 1 << 16;
  c.camera_paths = camera_paths;
  return c;
}

// The cap: a pass holds at most half a camera pass's worth of photon paths (default); N_min = N_max / 64
// (floored at 2^14: the spec's 2^16 assumed untargeted emission, schedule.hpp).
TEST(CausticsSchedule, MapSizeCappedByCameraPasses) {
  ScheduleConfig c;
  c.n_max = 1 << 22;
  c.camera_paths = 1280 * 720;
  EXPECT_EQ(c.effective_max(), 1280u * 720 / 2);
  EXPECT_EQ(c.effective_min(), 16384u);  // the floor: 1280 * 720 / 2 / 64 is below it
  c.camera_paths = 4096 * 4096;
  EXPECT_EQ(c.effective_min(), (1u << 22) / 64);
  c.n_max = 1 << 24;  // a larger N_max (here the cap, 4096^2 / 2): N_min = N_max / 64 above the floor
  EXPECT_EQ(c.effective_max(), 4096u * 4096 / 2);
  EXPECT_EQ(c.effective_min(), 4096u * 4096 / 2 / 64);
  c.n_max = 1 << 22;
  c.camera_paths = 10000 * 10000;
  EXPECT_EQ(c.effective_max(), 1u << 22);
  c.photon_paths_per_camera_path = 4;
  c.camera_paths = 640 * 360;
  EXPECT_EQ(c.effective_max(), 4u * 640 * 360);
  c.photon_paths_per_camera_path = 1;
  c.camera_paths = 80 * 45;
  EXPECT_EQ(c.effective_max(), 80u * 45);
  EXPECT_EQ(c.effective_min(), 80u * 45);
  PhotonSchedule s(c);
  EXPECT_EQ(s.plan(1), 1u << 16);  // the probe is not capped
  s.pass_done(1, 1 << 16, 10);
  EXPECT_EQ(s.next_pass(), 1u + 18);  // 65536 / 3600 = 18 camera passes
  s.iteration_done(18, {1.0, 1.0});
  EXPECT_EQ(s.plan(19), 80u * 45);
  s.pass_done(19, 80 * 45, 10);
  EXPECT_EQ(s.next_pass(), 20u);  // then one photon pass per camera pass
}

TEST(CausticsSchedule, ProbeThenBudgetFromUsefulPixels) {
  PhotonSchedule s(config(200000));
  EXPECT_EQ(s.plan(1), 1u << 16);  // the probe
  s.pass_done(1, 1 << 16, 500);
  EXPECT_TRUE(s.map_active());
  s.iteration_done(1, {0.25, 0.25});
  EXPECT_EQ(s.plan(2), uint64_t(0.25 * (1 << 20)));  // u * N_max
  s.pass_done(2, uint64_t(0.25 * (1 << 20)), 1000);
  // 262144 photon paths vs 200000 camera paths: one pass serves round(1.31) = 1 iteration.
  s.iteration_done(2, {1e-6, 1e-6});
  EXPECT_EQ(s.plan(3), (1u << 20) / 64);  // clamped to N_min
  s.pass_done(3, (1 << 20) / 64, 10);
  s.iteration_done(3, {1.0, 1.0});
  EXPECT_EQ(s.plan(4), 1u << 20);  // N_max
  EXPECT_EQ(s.passes(), 3u);
}

// The cap on stored photons (default 1/8 per camera path) binds through the previous pass's photons per
// path: a scene storing ~1 photon per path (the pool) gets fewer paths, one storing 0.2 none.
TEST(CausticsSchedule, StoredPhotonsCappedByCameraPasses) {
  ScheduleConfig c;
  c.camera_paths = 640 * 360;
  PhotonSchedule s(c);
  EXPECT_EQ(s.plan(1), 1u << 16);
  s.pass_done(1, 1 << 16, 1 << 16);  // 1 photon per path
  s.iteration_done(1, {1.0, 1.0});
  EXPECT_EQ(s.plan(2), 28800u);          // 230400 / 8 stored photons: 28800 paths, not N_max = 115200
  s.pass_done(2, 28800, 28800 * 3 / 2);  // 1.5 per path: two thirds of the paths
  s.iteration_done(2, {1.0, 1.0});
  EXPECT_EQ(s.plan(3), 19200u);
  s.pass_done(3, 19200, 19200 / 5);  // 0.2 per path: the cap is above N_max
  s.iteration_done(3, {1.0, 1.0});
  EXPECT_EQ(s.plan(4), 115200u);
  s.iteration_done(3, {0.25, 0.25});
  EXPECT_EQ(s.plan(4), 28800u);      // u N_max, under the cap
  s.pass_done(4, 28800, 0);          // a pass storing nothing keeps the last yield
  s.pass_done(5, 1 << 14, 1 << 17);  // 8 per path: the cap, but never below N_min
  s.iteration_done(5, {1.0, 1.0});
  EXPECT_EQ(s.plan(s.next_pass()), c.effective_min());
}

TEST(CausticsSchedule, LargePassesServeSeveralIterations) {
  PhotonSchedule s(config(4096));  // a small image: 4096 camera paths per iteration
  s.pass_done(1, 1 << 16, 100);    // probe: 65536 paths = 16 camera passes
  for (uint64_t i = 1; i < 17; ++i) {
    s.iteration_done(i, {0.5, 0.5});
    EXPECT_EQ(s.plan(i + 1), i + 1 < 17 ? 0u : uint64_t(0.5 * (1 << 20))) << i;
  }
}

TEST(CausticsSchedule, BackOffWhenUseless) {
  PhotonSchedule s(config(100000));
  s.pass_done(1, 1 << 16, 0);  // nothing stored
  EXPECT_FALSE(s.map_active());
  EXPECT_EQ(s.idle_level(), 1u);
  EXPECT_EQ(s.plan(2), 0u);
  EXPECT_EQ(s.plan(3), (1u << 20) / 64);  // after 2^1 iterations without photons, N_min
  s.pass_done(3, (1 << 20) / 64, 5);      // photons, but no useful pixel
  s.iteration_done(3, {0.0, 0.0});
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
  s.iteration_done(s.next_pass(), {0.01, 0.01});
  EXPECT_EQ(s.idle_level(), 0u);
  EXPECT_TRUE(s.map_active());
}

// The budget follows the pixels where merges bring over 10 % of the light; pixels where they bring
// only 1-10 % keep the map alive at N_min instead of backing off.
TEST(CausticsSchedule, FaintMergesKeepTheMinimumBudget) {
  PhotonSchedule s(config(100000));
  s.pass_done(1, 1 << 16, 500);
  s.iteration_done(1, {0.0, 0.3});  // no pixel over 10 %, 30 % over 1 %
  EXPECT_TRUE(s.map_active());
  EXPECT_EQ(s.idle_level(), 0u);
  EXPECT_EQ(s.plan(2), (1u << 20) / 64);  // N_min, every iteration
  s.pass_done(2, (1 << 20) / 64, 50);
  s.iteration_done(2, {0.125, 0.5});
  EXPECT_EQ(s.plan(3), uint64_t(0.125 * (1 << 20)));  // the budget reads the 10 % ratio only
  s.pass_done(3, uint64_t(0.125 * (1 << 20)), 50);
  s.iteration_done(3, {0.0, 0.0});
  EXPECT_FALSE(s.map_active());
  EXPECT_EQ(s.idle_level(), 1u);
}

}  // namespace
}  // namespace nimbus::caustics
