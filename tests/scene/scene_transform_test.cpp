// Transforms are applied at parse time: shapes leave the parser in world space with outward normals.
#include <gtest/gtest.h>

#include <algorithm>

#include "scene_test_support.hpp"

namespace nimbus::test {
namespace scene_transform_test {

void expect_vec(const Vec3f &actual, const Vec3f &expected, float tolerance = 1e-5f) {
  EXPECT_NEAR(actual.x, expected.x, tolerance) << "x";
  EXPECT_NEAR(actual.y, expected.y, tolerance) << "y";
  EXPECT_NEAR(actual.z, expected.z, tolerance) << "z";
}

// The one object of a scene whose only material is `white`.
ShapeDesc one_object(const std::string &object) {
  const SceneDesc scene = parse_ok("materials: { white: { type: diffuse } }\nobjects:\n  - " + object + "\n");
  EXPECT_EQ(scene.shapes.size(), 1u);
  return scene.shapes.empty() ? ShapeDesc{} : scene.shapes[0];
}

Vec3f geometric_normal(const MeshData &mesh, size_t triangle) {
  const Vec3f &p0 = mesh.positions[mesh.indices[3 * triangle]];
  const Vec3f &p1 = mesh.positions[mesh.indices[3 * triangle + 1]];
  const Vec3f &p2 = mesh.positions[mesh.indices[3 * triangle + 2]];
  return normalize(cross(p1 - p0, p2 - p0));
}

Vec3f centroid(const MeshData &mesh, size_t triangle) {
  return (mesh.positions[mesh.indices[3 * triangle]] + mesh.positions[mesh.indices[3 * triangle + 1]] +
          mesh.positions[mesh.indices[3 * triangle + 2]]) /
         3.0f;
}

bool has_vertex(const MeshData &mesh, const Vec3f &p) {
  return std::any_of(mesh.positions.begin(), mesh.positions.end(),
                     [&](const Vec3f &q) { return length(q - p) < 1e-5f; });
}

// Every triangle's geometric normal points away from `center`: for a convex solid, the centre lies behind
// every face plane.
void expect_outward(const MeshData &mesh, const Vec3f &center) {
  for (size_t t = 0; t < mesh.indices.size() / 3; ++t)
    EXPECT_GT(dot(geometric_normal(mesh, t), centroid(mesh, t) - center), 0.1f) << "triangle " << t;
}

TEST(SceneTransform, RectangleIsTwoTrianglesFacingPlusZ) {
  const ShapeDesc rect = one_object("{ shape: rectangle, size: [2, 1], material: white }");
  EXPECT_EQ(rect.type, ShapeType::Rectangle);
  ASSERT_EQ(rect.mesh.indices.size(), 6u);
  for (const Vec3f &corner : {Vec3f(-1, -0.5f, 0), Vec3f(1, -0.5f, 0), Vec3f(1, 0.5f, 0), Vec3f(-1, 0.5f, 0)})
    EXPECT_TRUE(has_vertex(rect.mesh, corner));
  expect_vec(geometric_normal(rect.mesh, 0), {0, 0, 1});
  expect_vec(geometric_normal(rect.mesh, 1), {0, 0, 1});
}

TEST(SceneTransform, RectangleRotatedNinetyDegreesAboutZThenTranslated) {
  // Size [2, 1]: the long side along x turns to lie along y; then the centre moves to (5, 0, 1).
  for (const char *rotate : {"[0, 0, 90]", "[[0, 0, 1, 90]]", "[0, 0, 1, 90]"}) {
    const ShapeDesc rect = one_object(std::string("{ shape: rectangle, size: [2, 1], material: white, ") +
                                      "transform: { rotate: " + rotate + ", translate: [5, 0, 1] } }");
    SCOPED_TRACE(rotate);
    for (const Vec3f &corner : {Vec3f(5.5f, -1, 1), Vec3f(5.5f, 1, 1), Vec3f(4.5f, 1, 1), Vec3f(4.5f, -1, 1)})
      EXPECT_TRUE(has_vertex(rect.mesh, corner)) << corner.x << " " << corner.y << " " << corner.z;
    expect_vec(geometric_normal(rect.mesh, 0), {0, 0, 1});
  }
}

TEST(SceneTransform, RectangleRotatedAboutXFacesMinusY) {
  const ShapeDesc rect =
      one_object("{ shape: rectangle, size: [1, 1], material: white, transform: { rotate: [90, 0, 0] } }");
  expect_vec(geometric_normal(rect.mesh, 0), {0, -1, 0});
  expect_vec(geometric_normal(rect.mesh, 1), {0, -1, 0});
}

TEST(SceneTransform, EulerAnglesApplyAboutXThenYThenZ) {
  // x then y: the +z normal goes to -y (about x by 90), which rotating about y leaves alone. The other
  // order (y then x) would give (1, 0, 0).
  const ShapeDesc rect =
      one_object("{ shape: rectangle, size: [1, 1], material: white, transform: { rotate: [90, 90, 0] } }");
  expect_vec(geometric_normal(rect.mesh, 0), {0, -1, 0});
}

TEST(SceneTransform, ScaleThenRotateThenTranslate) {
  // The corner (0.5, 0.5, 0) scales to (1, 0.5, 0), rotates about z to (-0.5, 1, 0), translates to (-0.5, 1,
  // 3).
  const ShapeDesc rect = one_object(
      "{ shape: rectangle, size: [1, 1], material: white, "
      "transform: { translate: [0, 0, 3], rotate: [0, 0, 90], scale: [2, 1, 1] } }");
  EXPECT_TRUE(has_vertex(rect.mesh, {-0.5f, 1, 3}));
}

TEST(SceneTransform, MatrixEqualsTheSameTranslateRotateScale) {
  const ShapeDesc trs = one_object(
      "{ shape: box, size: [1, 2, 3], material: white, transform: { translate: [1, 2, 3], rotate: [0, 0, 90] "
      "} }");
  const ShapeDesc matrix = one_object(
      "{ shape: box, size: [1, 2, 3], material: white, "
      "transform: { matrix: [0, -1, 0, 1,  1, 0, 0, 2,  0, 0, 1, 3,  0, 0, 0, 1] } }");
  ASSERT_EQ(trs.mesh.positions.size(), matrix.mesh.positions.size());
  for (size_t i = 0; i < trs.mesh.positions.size(); ++i)
    expect_vec(matrix.mesh.positions[i], trs.mesh.positions[i]);
}

TEST(SceneTransform, BoxHasTwelveOutwardTriangles) {
  const ShapeDesc box = one_object("{ shape: box, size: [1, 2, 3], material: white }");
  EXPECT_EQ(box.type, ShapeType::Box);
  ASSERT_EQ(box.mesh.indices.size(), 36u);
  expect_outward(box.mesh, {0, 0, 0});
  for (const Vec3f &corner : {Vec3f(0.5f, 1, 1.5f), Vec3f(-0.5f, -1, -1.5f)})
    EXPECT_TRUE(has_vertex(box.mesh, corner));
}

TEST(SceneTransform, TransformedBoxStaysOutward) {
  const ShapeDesc box = one_object(
      "{ shape: box, size: [1, 1, 1], material: white, "
      "transform: { translate: [3, 0, 0], rotate: [[1, 1, 0, 30], [0, 0, 1, 45]], scale: [2, 0.5, 1] } }");
  expect_outward(box.mesh, {3, 0, 0});
}

TEST(SceneTransform, MirroredBoxStaysOutward) {
  // A negative scale reverses triangle winding; the parser reverses it back.
  const ShapeDesc box =
      one_object("{ shape: box, size: [1, 1, 1], material: white, transform: { scale: [-1, 1, 1] } }");
  expect_outward(box.mesh, {0, 0, 0});
}

TEST(SceneTransform, DiskCentreNormalAndRadiusFollowTheTransform) {
  const ShapeDesc disk = one_object(
      "{ shape: disk, radius: 0.5, material: white, "
      "transform: { rotate: [90, 0, 0], scale: 2, translate: [1, 2, 3] } }");
  EXPECT_EQ(disk.type, ShapeType::Disk);
  expect_vec(disk.center, {1, 2, 3});
  expect_vec(disk.normal, {0, -1, 0});
  EXPECT_NEAR(disk.radius, 1.0f, 1e-6f);
}

TEST(SceneTransform, SphereCentreAndRadiusFollowTheTransform) {
  const ShapeDesc sphere = one_object(
      "{ shape: sphere, center: [1, 0, 0], radius: 0.5, material: white, "
      "transform: { rotate: [0, 0, 90], scale: 3, translate: [0, 0, 1] } }");
  expect_vec(sphere.center, {0, 3, 1});
  EXPECT_NEAR(sphere.radius, 1.5f, 1e-6f);
}

TEST(SceneTransform, MeshNormalsUseTheInverseTranspose) {
  // A 45-degree slope scaled by 2 along x: the normal (1, 0, 1)/sqrt2 becomes (1, 0, 2)/sqrt5, not (2, 0, 1).
  const ShapeDesc mesh = one_object(R"(shape: mesh
    material: white
    positions: [[0, 0, 1], [1, 0, 0], [0, 1, 1]]
    normals: [[1, 0, 1], [1, 0, 1], [1, 0, 1]]
    indices: [0, 1, 2]
    transform: { scale: [2, 1, 1] })");
  ASSERT_EQ(mesh.mesh.normals.size(), 3u);
  expect_vec(mesh.mesh.normals[0], normalize(Vec3f(1, 0, 2)));
  expect_vec(mesh.mesh.positions[1], {2, 0, 0});
}

}  // namespace scene_transform_test
}  // namespace nimbus::test
