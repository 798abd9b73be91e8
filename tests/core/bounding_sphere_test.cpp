// core/bounding_sphere.hpp: Ritter's sphere encloses every point (points on a sphere's surface, a
// flat disk, clusters far apart, huge coordinates) and is close to the smallest enclosing sphere where
// that is known.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include <nimbus/cpp/bounding_sphere.hpp>
#include <nimbus/cpp/sampling.hpp>

namespace nimbus {
namespace bounding_sphere_test {

std::vector<Vec3f> on_sphere(const Vec3f &c, float r, int n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0, 1);
  std::vector<Vec3f> pts;
  for (int i = 0; i < n; ++i) pts.push_back(c + sample_uniform_sphere(u(rng), u(rng)) * r);
  return pts;
}

void expect_encloses(const Sphere &s, const std::vector<Vec3f> &pts) {
  for (const Vec3f &p : pts) ASSERT_LE(length(p - s.center), s.radius) << p.x << " " << p.y << " " << p.z;
}

TEST(BoundingSphere, EmptyAndSinglePoint) {
  EXPECT_TRUE(ritter_bounding_sphere({}).empty());
  const std::vector<Vec3f> one{Vec3f(1, 2, 3)};
  const Sphere s = ritter_bounding_sphere(one);
  EXPECT_FALSE(s.empty());
  EXPECT_EQ(s.radius, 0.0f);
}

// The photons' sharp hits on a glass sphere: the box around them would give radius r sqrt(3).
TEST(BoundingSphere, PointsOnASphereGiveNearlyThatSphere) {
  for (const float scale : {1e-3f, 1.0f, 1e4f}) {
    const Vec3f c(0.3f * scale, -2 * scale, 5 * scale);
    const auto pts = on_sphere(c, 0.5f * scale, 5000, 7);
    const Sphere s = ritter_bounding_sphere(pts);
    expect_encloses(s, pts);
    EXPECT_LT(s.radius, 0.5f * scale * 1.1f) << "scale " << scale;
    EXPECT_LT(length(s.center - c), 0.1f * scale);
  }
}

TEST(BoundingSphere, EnclosesFlatAndClusteredSets) {
  std::vector<Vec3f> pts = on_sphere(Vec3f(0, 0, 0), 0.1f, 500, 3);
  const auto far = on_sphere(Vec3f(40, 0, 0), 0.1f, 500, 4);
  pts.insert(pts.end(), far.begin(), far.end());
  for (int i = 0; i < 500; ++i) pts.push_back(Vec3f(20 + std::cos(float(i)), std::sin(float(i)) * 19.0f, 0));
  const Sphere s = ritter_bounding_sphere(pts);
  expect_encloses(s, pts);
  EXPECT_LT(s.radius, 20.1f * 1.15f);  // the smallest is ~20.1 (the two clusters' extremes)
}

}  // namespace bounding_sphere_test
}  // namespace nimbus
