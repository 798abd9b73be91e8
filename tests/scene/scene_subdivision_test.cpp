// `shape: subdivision` — OpenSubdiv refinement of a cage at load time: face counts per level, vertices on
// the Catmull-Clark limit surface, creases, Loop, `level: auto` and the cage's errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "scene_test_support.hpp"

namespace nimbus::test {
namespace scene_subdivision_test {

// The unit cube centred at the origin, faces counter-clockwise seen from outside.
const std::string kCubePositions =
    "[[-0.5, -0.5, -0.5], [0.5, -0.5, -0.5], [0.5, 0.5, -0.5], [-0.5, 0.5, -0.5], "
    "[-0.5, -0.5, 0.5], [0.5, -0.5, 0.5], [0.5, 0.5, 0.5], [-0.5, 0.5, 0.5]]";
const std::string kCubeFaces =
    "[[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [2, 3, 7, 6], [0, 4, 7, 3], [1, 2, 6, 5]]";
const std::string kAllCubeEdges =
    "[[0, 1, 10], [1, 2, 10], [2, 3, 10], [3, 0, 10], [4, 5, 10], [5, 6, 10], [6, 7, 10], [7, 4, 10], "
    "[0, 4, 10], [1, 5, 10], [2, 6, 10], [3, 7, 10]]";

std::string cube(const std::string &keys) {
  return "materials: { white: { type: diffuse } }\nobjects:\n  - { shape: subdivision, material: white, "
         "positions: " +
         kCubePositions + ", faces: " + kCubeFaces + keys + " }\n";
}

MeshData cube_mesh(const std::string &keys) {
  const SceneDesc scene = parse_ok(cube(keys));
  return scene.shapes.empty() ? MeshData{} : scene.shapes[0].mesh;
}

// The Catmull-Clark limit surface of the unit cube lies between its face centres' limit points, at
// 0.41975 from the centre ((16 * 0.5 + 16 * 0.375 + 4 * 5 / 18) / 36), and its corners' limit points, at
// |(1, 1, 1) / 4| = 0.43301 (limit mask (n^2 v + 4 sum e + sum f) / (n (n + 5)) with n = 3).
constexpr float kLimitMin = 0.419753f, kLimitMax = 0.433013f;

TEST(SceneSubdivision, CubeFaceCountsPerLevel) {
  for (int level = 0; level <= 3; ++level) {
    const MeshData m = cube_mesh(", level: " + std::to_string(level));
    const size_t quads = 6u << (2 * level);
    EXPECT_EQ(m.indices.size(), 3 * 2 * quads) << "level " << level;
    EXPECT_EQ(m.positions.size(), quads + 2) << "Euler: V = F + 2 for a closed quad mesh";
    EXPECT_EQ(m.normals.size(), m.positions.size());
    EXPECT_TRUE(m.uvs.empty());
  }
}

TEST(SceneSubdivision, VerticesLieOnTheCatmullClarkLimitSurface) {
  const MeshData m = cube_mesh(", level: 3");
  float lo = 1, hi = 0;
  for (size_t i = 0; i < m.positions.size(); ++i) {
    const float r = length(m.positions[i]);
    lo = std::min(lo, r);
    hi = std::max(hi, r);
    EXPECT_NEAR(length(m.normals[i]), 1, 1e-5f);
    EXPECT_GT(dot(m.normals[i], m.positions[i]), 0.9f * r) << "outward and close to radial on a near-sphere";
  }
  EXPECT_NEAR(lo, kLimitMin, 1e-5f);
  EXPECT_NEAR(hi, kLimitMax, 1e-5f);
  // Triangles face outward (the cage's winding).
  for (size_t t = 0; t < m.indices.size(); t += 3) {
    const Vec3f &a = m.positions[m.indices[t]], &b = m.positions[m.indices[t + 1]],
                &c = m.positions[m.indices[t + 2]];
    ASSERT_GT(dot(cross(b - a, c - a), a + b + c), 0);
  }
}

// The triangles' centroids (chords of the surface) approach the limit surface as the level grows.
TEST(SceneSubdivision, RefinementConvergesToTheLimit) {
  float previous_gap = 1;
  for (int level = 0; level <= 4; ++level) {
    const MeshData m = cube_mesh(", level: " + std::to_string(level));
    float gap = 0;
    for (size_t t = 0; t < m.indices.size(); t += 3) {
      const Vec3f c =
          (m.positions[m.indices[t]] + m.positions[m.indices[t + 1]] + m.positions[m.indices[t + 2]]) / 3.0f;
      gap = std::max(gap, kLimitMin - length(c));
    }
    EXPECT_LT(gap, previous_gap) << "level " << level;
    previous_gap = gap;
  }
  EXPECT_LT(previous_gap, 2e-3f);
}

TEST(SceneSubdivision, InfinitelySharpCreasesKeepEdgesOnTheCage) {
  const int level = 2;
  const MeshData m = cube_mesh(", level: 2, creases: " + kAllCubeEdges);
  size_t on_edges = 0;
  for (const Vec3f &p : m.positions) {
    const float ax = std::abs(p.x), ay = std::abs(p.y), az = std::abs(p.z);
    EXPECT_NEAR(std::max({ax, ay, az}), 0.5f, 1e-6f) << "every vertex stays on the cube";
    on_edges +=
        (std::abs(ax - 0.5f) < 1e-6f) + (std::abs(ay - 0.5f) < 1e-6f) + (std::abs(az - 0.5f) < 1e-6f) >= 2;
  }
  // Every refined vertex of the 12 cage edges stays on its edge: 8 corners and 2^L - 1 per edge.
  EXPECT_EQ(on_edges, 8 + 12 * ((1u << level) - 1));
}

TEST(SceneSubdivision, SharperCreaseStaysCloserToTheCageEdge) {
  // The top front edge (4, 5) runs along x at y = -0.5, z = 0.5; its midpoint is (0, -0.5, 0.5). Alone, it
  // ends in darts (one sharp edge each), whose smooth rule pulls the ends of the crease curve inward: the
  // curve stays sharp but leaves the cage edge (about 0.1 at its middle; 0.28 for a smooth edge).
  float previous = 1, smooth = 0;
  for (const char *sharpness : {"0", "1", "3", "10"}) {
    const MeshData m = cube_mesh(std::string(", level: 3, creases: [[4, 5, ") + sharpness + "]]");
    float closest = 1;
    for (const Vec3f &p : m.positions) closest = std::min(closest, length(p - Vec3f(0, -0.5f, 0.5f)));
    EXPECT_LT(closest, previous) << "sharpness " << sharpness;
    if (smooth == 0) smooth = closest;
    previous = closest;
  }
  EXPECT_LT(previous, 0.4f * smooth);
}

TEST(SceneSubdivision, LoopOnTriangles) {
  // Octahedron.
  const std::string octahedron =
      "materials: { white: { type: diffuse } }\nobjects:\n  - { shape: subdivision, material: white, scheme: "
      "loop, "
      "positions: [[1, 0, 0], [0, 1, 0], [-1, 0, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]], faces: [[0, 1, 4], "
      "[1, 2, 4], "
      "[2, 3, 4], [3, 0, 4], [1, 0, 5], [2, 1, 5], [3, 2, 5], [0, 3, 5]], level: ";
  for (int level = 0; level <= 2; ++level) {
    const MeshData m = parse_ok(octahedron + std::to_string(level) + " }\n").shapes.at(0).mesh;
    EXPECT_EQ(m.indices.size(), 3u * (8u << (2 * level)));
    for (size_t i = 0; i < m.positions.size(); ++i) EXPECT_GT(dot(m.normals[i], m.positions[i]), 0);
  }
}

TEST(SceneSubdivision, ObjCageEqualsInlineCage) {
  TempDir dir;
  const std::string obj = dir.write("cage.obj",
                                    "v -0.5 -0.5 -0.5\nv 0.5 -0.5 -0.5\nv 0.5 0.5 -0.5\nv -0.5 0.5 -0.5\n"
                                    "v -0.5 -0.5 0.5\nv 0.5 -0.5 0.5\nv 0.5 0.5 0.5\nv -0.5 0.5 0.5\n"
                                    "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 3 4 8 7\nf 1 5 8 4\nf 2 3 7 6\n");
  const SceneDesc scene = parse_ok(
      "materials: { white: { type: diffuse } }\nobjects:\n"
      "  - { shape: subdivision, material: white, file: " +
      obj + ", level: 2 }\n");
  const MeshData inline_mesh = cube_mesh(", level: 2");
  EXPECT_EQ(scene.shapes.at(0).mesh.positions, inline_mesh.positions);
  EXPECT_EQ(scene.shapes.at(0).mesh.indices, inline_mesh.indices);
}

// The level from the triangle count 12 * 4^L of the cube.
int cube_level(const MeshData &m) {
  return int(std::lround(std::log2(double(m.indices.size() / 3) / 12) / 2));
}

TEST(SceneSubdivision, AutoLevelFollowsTheCamera) {
  const auto level_at = [](float distance, const std::string &transform = "") {
    return cube_level(parse_ok("render: { resolution: [512, 256] }\ncamera: { position: [0, " +
                               std::to_string(-distance) + ", 0], look_at: [0, 0, 0], fov: 45 }\n" +
                               cube(", level: auto" + transform))
                          .shapes.at(0)
                          .mesh);
  };
  // Focal length 512 / (2 tan 22.5 deg) = 618 pixels; the nearest unit edges are 99.5 away: 6.2 pixels.
  EXPECT_EQ(level_at(100), 3);
  EXPECT_EQ(level_at(100, ", transform: { scale: 2 }"), 4) << "edges measured in world space";
  EXPECT_EQ(level_at(1000), 0);
  EXPECT_EQ(level_at(3), 6) << "clamped";
  int previous = -1;
  for (float d : {2000.f, 300.f, 100.f, 30.f, 10.f, 3.f}) {
    const int level = level_at(d);
    EXPECT_GE(level, previous) << "distance " << d;
    previous = level;
  }
  // `auto` is the default.
  EXPECT_EQ(cube_level(parse_ok("camera: { position: [0, -100, 0], look_at: [0, 0, 0], fov: 45 }\n"
                                "render: { resolution: [512, 512] }\n" +
                                cube(""))
                           .shapes.at(0)
                           .mesh),
            3);
}

TEST(SceneSubdivisionErrors, Scheme) {
  EXPECT_TRUE(
      fails_at(cube(", scheme: loop"), 3, 306, "objects[0].scheme",
               "loop subdivides triangles only, but face 0 of the cage has 4 vertices; use catmull-clark"));
  EXPECT_TRUE(fails_at(cube(", scheme: doo-sabin"), 3, 306, "objects[0].scheme",
                       "unknown subdivision scheme 'doo-sabin'; known: catmull-clark, loop"));
}

TEST(SceneSubdivisionErrors, Level) {
  EXPECT_TRUE(fails_at(cube(", level: 7"), 3, 305, "objects[0].level", "must be in [0, 6] (got 7)"));
  EXPECT_TRUE(fails_at(cube(", level: high"), 3, 305, "objects[0].level",
                       "expected an integer in [0, 6] or auto, got 'high'"));
}

TEST(SceneSubdivisionErrors, TooManyTriangles) {
  // A 65 x 65 grid of quads (an OBJ file: as YAML it would take longer to parse than everything else here):
  // level 6 would make 2 * 4 * 4225 * 4^5 triangles.
  TempDir dir;
  std::string obj;
  for (int y = 0; y <= 65; ++y)
    for (int x = 0; x <= 65; ++x) obj += "v " + std::to_string(x) + " " + std::to_string(y) + " 0\n";
  for (int y = 0; y < 65; ++y)
    for (int x = 0; x < 65; ++x) {
      const int v = y * 66 + x + 1;
      obj += "f " + std::to_string(v) + " " + std::to_string(v + 1) + " " + std::to_string(v + 67) + " " +
             std::to_string(v + 66) + "\n";
    }
  const std::string yaml =
      "materials: { white: { type: diffuse } }\nobjects:\n  - shape: subdivision\n"
      "    material: white\n    level: 6\n    file: " +
      dir.write("grid.obj", obj) + "\n";
  EXPECT_TRUE(
      fails_at(yaml, 5, 12, "objects[0].level", "level 6 would make 34611200 triangles (at most 33554432)"));
}

TEST(SceneSubdivisionErrors, Creases) {
  EXPECT_TRUE(fails_at(cube(", creases: [[0, 6, 10]]"), 3, 308, "objects[0].creases[0]",
                       "vertices 0 and 6 are not the ends of a cage edge"));
  EXPECT_TRUE(fails_at(cube(", creases: [[0, 1, 11]]"), 3, 315, "objects[0].creases[0][2]",
                       "must be in [0, 10] (got 11)"));
  EXPECT_TRUE(fails_at(cube(", creases: [[0, 1]]"), 3, 308, "objects[0].creases[0]",
                       "expected [v0, v1, sharpness] (3 elements), got 2 elements"));
}

TEST(SceneSubdivisionErrors, Faces) {
  const std::string start =
      "materials: { white: { type: diffuse } }\nobjects:\n  - { shape: subdivision, material: white, "
      "positions: [[0, 0, 0], [1, 0, 0], [0, 1, 0]], faces: ";
  EXPECT_TRUE(fails_at(start + "[[0, 1]] }\n", 3, 98, "objects[0].faces[0]",
                       "a face needs at least 3 vertices, got 2"));
  EXPECT_TRUE(fails_at(start + "[[0, 1, 1]] }\n", 3, 105, "objects[0].faces[0][2]",
                       "vertex 1 appears twice in the face"));
  EXPECT_TRUE(fails_at(start + "[[0, 1, 3]] }\n", 3, 105, "objects[0].faces[0][2]",
                       "vertex index 3 is out of range: the cage has 3 positions"));
  EXPECT_TRUE(fails_at(start + "[0, 1, 2] }\n", 3, 98, "objects[0].faces[0]",
                       "expected a face [i, j, k, ...], got '0'"));
  EXPECT_TRUE(fails_at(
      "materials: { white: { type: diffuse } }\nobjects:\n  - { shape: subdivision, material: white }\n", 3,
      5, "objects[0]", "a subdivision surface needs 'file', or 'positions' and 'faces'"));
}

TEST(SceneSubdivisionErrors, CageFile) {
  TempDir dir;
  const std::string missing = (dir.path() / "none.obj").string();
  const std::string head =
      "materials: { white: { type: diffuse } }\nobjects:\n  - { shape: subdivision, material: white, file: ";
  EXPECT_TRUE(fails_at(head + missing + " }\n", 3, 50, "objects[0].file",
                       "cannot load cage '" + missing + "': No such file or directory"));
  const std::string degenerate = dir.write("degenerate.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 2\n");
  EXPECT_TRUE(fails_at(head + degenerate + " }\n", 3, 50, "objects[0].file",
                       "face 2 needs at least 3 distinct vertices"));
  EXPECT_TRUE(fails_at(head + degenerate + ", faces: [[0, 1, 2]] }\n", 3, 52 + int(degenerate.size()),
                       "objects[0].faces", "cannot be combined with 'file'"));
}

}  // namespace scene_subdivision_test
}  // namespace nimbus::test
