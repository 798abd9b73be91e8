// Where lookups may take the whole shutter (moving_bounds.hpp): a segment is still when it meets no
// moving object's bounds, ends included; a first vertex's segment counts every lens point (the bounds
// grown by the lens's radius, so that a splat from the lens's rim and the camera path from its centre
// agree); many moving objects become one box around them; a moving camera, untimed photons or a host
// without moving_bounds leave every lookup with its time window.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "moving_bounds.hpp"

namespace nimbus::caustics {
namespace moving_bounds_test {

using Box = MovingBounds::Box;

TEST(MovingBounds, SegmentsMeetBoxesEndsIncluded) {
  const Box b{{0, 0, 0}, {1, 1, 1}};
  EXPECT_TRUE(MovingBounds::meets(b, {-1, 0.5f, 0.5f}, {2, 0.5f, 0.5f})) << "through";
  EXPECT_TRUE(MovingBounds::meets(b, {0.5f, 0.5f, 0.5f}, {3, 3, 3})) << "from inside";
  EXPECT_TRUE(MovingBounds::meets(b, {-1, 0.5f, 0.5f}, {0.2f, 0.5f, 0.5f})) << "ending inside";
  EXPECT_FALSE(MovingBounds::meets(b, {-1, 0.5f, 0.5f}, {-0.1f, 0.5f, 0.5f})) << "stopping short";
  EXPECT_FALSE(MovingBounds::meets(b, {-1, 1.5f, 0.5f}, {2, 1.5f, 0.5f})) << "passing beside";
  EXPECT_FALSE(MovingBounds::meets(b, {-1, 0.5f, 2}, {2, 2.5f, 0.5f})) << "passing above a corner";
  EXPECT_TRUE(MovingBounds::meets(b, {-1, 0.5f, 2}, {2, 0.5f, -1})) << "diagonal through";
  // Brute force: sample points along random segments.
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.0f, 2.0f);
  for (int i = 0; i < 20000; ++i) {
    const Vec3f a{u(rng), u(rng), u(rng)}, c{u(rng), u(rng), u(rng)};
    bool inside = false;
    for (int k = 0; k <= 400 && !inside; ++k) {
      const Vec3f p = a + (c - a) * (float(k) / 400);
      inside = p.x > 0.001f && p.x < 0.999f && p.y > 0.001f && p.y < 0.999f && p.z > 0.001f && p.z < 0.999f;
    }
    if (inside) ASSERT_TRUE(MovingBounds::meets(b, a, c)) << "segment " << i;
  }
}

// Host stubs: a scene query serving `boxes` and a camera whose lens has `aperture` (0: a pinhole).
struct Stubs {
  static inline std::vector<nimbus_object_bounds_t> boxes;
  static inline uint32_t motion = NIMBUS_MOTION_GEOMETRY;
  static inline float aperture = 0;
  nimbus_host_scene_query_v1_t scene{};
  nimbus_host_camera_v1_t camera{};
  Stubs() {
    scene.struct_size = sizeof(scene);
    scene.moving_bounds = [](const nimbus_host_t *, nimbus_object_bounds_t *out, uint32_t capacity) {
      for (uint32_t i = 0; i < capacity && i < boxes.size(); ++i) out[i] = boxes[i];
      return uint32_t(boxes.size());
    };
    camera.struct_size = sizeof(camera);
    camera.shutter = [](const nimbus_host_t *, float *open, float *close) {
      *open = 0, *close = 1;
      return motion;
    };
    camera.resolution = [](const nimbus_host_t *, uint32_t *w, uint32_t *h) {
      *w = 64, *h = 32;
      return 0.01f;
    };
    // A lens in the plane z = 10, centred on the z axis; lens samples map to a square of half side
    // `aperture` (any map whose corners reach the rim serves).
    camera.generate_ray = [](const nimbus_host_t *, const nimbus_camera_sample_t *s, nimbus_ray_t *ray) {
      ray->org[0] = (2 * s->lens[0] - 1) * aperture, ray->org[1] = (2 * s->lens[1] - 1) * aperture;
      ray->org[2] = 10;
      ray->dir[0] = 0, ray->dir[1] = 0, ray->dir[2] = -1;
      return 1.0f;
    };
  }
  MovingBounds build(bool timed = true) const { return MovingBounds::of(nullptr, &scene, &camera, timed); }
};

nimbus_object_bounds_t box(Vec3f lo, Vec3f hi) {
  nimbus_object_bounds_t b{};
  lo.store(b.lo), hi.store(b.hi);
  return b;
}

TEST(MovingBounds, TheLensSegmentCountsEveryLensPoint) {
  Stubs s;
  Stubs::boxes = {box({1, -0.5f, 4}, {2, 0.5f, 5})};
  Stubs::motion = NIMBUS_MOTION_GEOMETRY;
  Stubs::aperture = 0;
  const MovingBounds pinhole = s.build();
  ASSERT_TRUE(pinhole.enabled());
  // From the pinhole (0, 0, 10) to the floor point (1.2, 0, 0): at z = 4.5 the segment is at x = 0.66,
  // beside the box.
  EXPECT_TRUE(pinhole.lens_segment_still({1.2f, 0, 0}));
  EXPECT_FALSE(pinhole.lens_segment_still({3, 0, 0})) << "x = 1.65 at z = 4.5: through the box";
  EXPECT_FALSE(pinhole.lens_segment_still({1.5f, 0, 4.5f})) << "the vertex inside the box";
  // A lens of radius 0.8: from its rim at x = 0.8 the same floor point's segment passes x = 1.02 at
  // z = 4.5, inside the box: no longer still.
  Stubs::aperture = 0.8f / std::sqrt(2.0f);
  const MovingBounds lens = s.build();
  EXPECT_FALSE(lens.lens_segment_still({1.2f, 0, 0}));
  EXPECT_TRUE(lens.lens_segment_still({-1.2f, 0, 0}));
  EXPECT_TRUE(lens.segment_still({1.2f, 0, 0}, {0, 0, 10})) << "a segment of its own ignores the lens";
}

TEST(MovingBounds, ManyMovingObjectsBecomeOneBox) {
  Stubs s;
  Stubs::aperture = 0;
  Stubs::motion = NIMBUS_MOTION_GEOMETRY;
  Stubs::boxes.clear();
  for (uint32_t i = 0; i < kMaxMovingBoxes + 1; ++i)
    Stubs::boxes.push_back(box({float(i), 0, 0}, {float(i) + 0.1f, 0.1f, 0.1f}));
  const MovingBounds m = s.build();
  ASSERT_EQ(m.boxes().size(), 1u);
  EXPECT_FALSE(m.segment_still({0.5f, 0.05f, -1}, {0.5f, 0.05f, 1})) << "between two objects: in the box";
  Stubs::boxes.pop_back();
  EXPECT_EQ(s.build().boxes().size(), size_t(kMaxMovingBoxes));
  EXPECT_TRUE(s.build().segment_still({0.5f, 0.05f, -1}, {0.5f, 0.05f, 1})) << "between two boxes";
}

TEST(MovingBounds, OffWhenTheCameraMovesOrPhotonsAreUntimed) {
  Stubs s;
  Stubs::boxes = {box({1, 1, 1}, {2, 2, 2})};
  Stubs::aperture = 0;
  Stubs::motion = NIMBUS_MOTION_GEOMETRY;
  EXPECT_TRUE(s.build().enabled());
  EXPECT_FALSE(s.build(false).enabled());
  Stubs::motion = NIMBUS_MOTION_GEOMETRY | NIMBUS_MOTION_CAMERA;
  const MovingBounds moving_camera = s.build();
  EXPECT_FALSE(moving_camera.enabled());
  EXPECT_FALSE(moving_camera.lens_segment_still({-5, -5, 0})) << "off: nothing is still";
  Stubs::motion = NIMBUS_MOTION_GEOMETRY;
  Stubs older;  // a 1.8 host's table ends before moving_bounds
  older.scene.struct_size = offsetof(nimbus_host_scene_query_v1_t, moving_bounds);
  EXPECT_FALSE(older.build().enabled());
}

}  // namespace moving_bounds_test
}  // namespace nimbus::caustics
