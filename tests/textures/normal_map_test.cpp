// Normal maps: the flat map changes nothing, a tilted one rotates the shading normal by its angle towards
// the tangent (red) or the bitangent (green, +v), mirrored uv layouts keep green meaning +v, and no input
// produces a NaN or a normal at or below the geometric horizon.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "materials/normal_map.hpp"
#include "materials/textured_materials.hpp"
#include "texture_fixtures.hpp"

namespace nimbus {
namespace normal_map_test {

using texture_test::ScratchDir;
using texture_test::texture_at;

float angle_between(const Vec3f &a, const Vec3f &b) { return std::atan2(length(cross(a, b)), dot(a, b)); }

Vec3f random_unit(std::mt19937 &rng) {
  std::normal_distribution<float> g;
  for (;;) {
    const Vec3f v{g(rng), g(rng), g(rng)};
    if (length(v) > 1e-3f) return normalize(v);
  }
}

// Texel of a tangent-space normal, as a float (EXR) normal map stores it.
Rgb encode(const Vec3f &n) { return n * 0.5f + Vec3f(0.5f); }

TEST(NormalMap, FlatTexelIsTheUnperturbedNormal) {
  EXPECT_EQ(decode_normal({0.5f, 0.5f, 1.0f}), Vec3f(0, 0, 1));
  std::mt19937 rng(7);
  for (int i = 0; i < 1000; ++i) {
    const Vec3f ns = random_unit(rng), dpdu = random_unit(rng) * 3.0f, dpdv = random_unit(rng);
    const Vec3f n = apply_normal_map({0, 0, 1}, ns, ns, dpdu, dpdv);
    EXPECT_LT(length(n - ns), 1e-6f);
  }
}

TEST(NormalMap, TiltRotatesTowardsTangentOrBitangent) {
  const Vec3f ns{0, 0, 1}, dpdu{2, 0, 0}, dpdv{0, 0.5f, 0};
  for (float degrees : {5.0f, 30.0f, 60.0f, 85.0f}) {
    const float t = radians(degrees);
    const Vec3f red =
        apply_normal_map(decode_normal(encode({std::sin(t), 0, std::cos(t)})), ns, ns, dpdu, dpdv);
    EXPECT_NEAR(angle_between(red, ns), t, 1e-5f) << degrees;
    EXPECT_NEAR(red.x, std::sin(t), 1e-5f);  // towards +u
    const Vec3f green =
        apply_normal_map(decode_normal(encode({0, std::sin(t), std::cos(t)})), ns, ns, dpdu, dpdv);
    EXPECT_NEAR(angle_between(green, ns), t, 1e-5f) << degrees;
    EXPECT_NEAR(green.y, std::sin(t), 1e-5f);  // towards +v
  }
}

TEST(NormalMap, MirroredUvKeepsGreenAlongPlusV) {
  const Vec3f ns{0, 0, 1}, dpdu{1, 0, 0}, dpdv{0, -1, 0};  // v runs against n x dpdu
  const Vec3f n = apply_normal_map(normalize(Vec3f{0, 0.5f, 1}), ns, ns, dpdu, dpdv);
  EXPECT_LT(n.y, 0);
}

TEST(NormalMap, TangentNeedNotBePerpendicular) {
  // Interpolated shading normals are not perpendicular to dpdu: the tangent is dpdu projected.
  const Vec3f ns = normalize(Vec3f{0.3f, 0, 1}), dpdu{1, 0, 0}, dpdv{0, 1, 0};
  const Vec3f n = apply_normal_map({0, 0, 1}, ns, Vec3f{0, 0, 1}, dpdu, dpdv);
  EXPECT_LT(length(n - ns), 1e-6f);
  const float t = radians(20);
  const Vec3f tilted = apply_normal_map({std::sin(t), 0, std::cos(t)}, ns, Vec3f{0, 0, 1}, dpdu, dpdv);
  EXPECT_NEAR(angle_between(tilted, ns), t, 1e-5f);
}

TEST(NormalMap, StaysAboveTheGeometricHorizon) {
  // The shading normal already leans 80 degrees away from ng; a further 40 degrees would cross it.
  const Vec3f ng{0, 0, 1};
  const float lean = radians(80), tilt = radians(40);
  const Vec3f ns{std::sin(lean), 0, std::cos(lean)};
  const Vec3f n = apply_normal_map({std::sin(tilt), 0, std::cos(tilt)}, ns, ng, {1, 0, 0}, {0, 1, 0});
  EXPECT_NEAR(length(n), 1.0f, 1e-6f);
  EXPECT_NEAR(dot(n, ng), kMinMappedCosine, 1e-6f);
  EXPECT_GT(n.x, 0.99f);  // clamped towards the side it leaned to, not flipped
}

TEST(NormalMap, NoInputGivesNaN) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u01(0, 1);
  const Rgb odd_texels[] = {{0, 0, 0}, {1, 1, 0}, {0.5f, 0.5f, 0.5f}, {0.5f, 0.5f, 0}, {1, 0.5f, 0.5f}};
  const Vec3f odd_tangents[] = {{0, 0, 0}, {1e-30f, 0, 0}, {0, 0, 1}, {1e30f, 1e30f, 0}};
  for (int i = 0; i < 20000; ++i) {
    const Vec3f ng = random_unit(rng);
    Vec3f ns = random_unit(rng);
    if (dot(ns, ng) < 0) ns = -ns;  // the interaction's contract: same side
    const Rgb texel = i % 4 == 0 ? odd_texels[size_t(i / 4) % 5] : Rgb{u01(rng), u01(rng), u01(rng)};
    const Vec3f dpdu = i % 3 == 0 ? odd_tangents[size_t(i / 3) % 4] : random_unit(rng);
    const Vec3f dpdv = i % 5 == 0 ? Vec3f(0.0f) : random_unit(rng);
    const Vec3f n = apply_normal_map(decode_normal(texel), ns, ng, dpdu, dpdv);
    ASSERT_TRUE(is_finite(n)) << i;
    ASSERT_NEAR(length(n), 1.0f, 1e-4f) << i;
    ASSERT_GE(dot(n, ng), kMinMappedCosine - 1e-4f) << i;
  }
}

// The same through image files and TexturedMaterials.
class NormalMapFile : public ::testing::Test {
 protected:
  Vec3f shade(const std::string &file, Vec3f ns = {0, 0, 1}) {
    MaterialDesc m;
    m.normal_map = texture_at(file);
    auto built = TexturedMaterials::build({m});
    EXPECT_TRUE(built.ok()) << (built.ok() ? "" : built.error().message);
    if (!built.ok()) return {};
    EXPECT_TRUE(built.value()->has_normal_map(0));
    return built.value()->shading_normal(0, {0.3f, 0.7f}, ns, {0, 0, 1}, {1, 0, 0}, {0, 1, 0});
  }
  ScratchDir dir;
};

TEST_F(NormalMapFile, FlatExrLeavesNsUnchanged) {
  std::vector<float> px;
  for (int i = 0; i < 4; ++i) px.insert(px.end(), {0.5f, 0.5f, 1.0f});
  texture_test::write_exr(dir.file("flat.exr"), 2, 2, 3, px);
  EXPECT_EQ(shade(dir.file("flat.exr")), Vec3f(0, 0, 1));
  const Vec3f leaning = normalize(Vec3f{0.2f, -0.1f, 1});
  EXPECT_LT(length(shade(dir.file("flat.exr"), leaning) - leaning), 1e-6f);
}

TEST_F(NormalMapFile, Flat8BitPngIsWithinHalfADegree) {
  // 8 bits cannot store 0.5: the customary 128 is 0.0039 off, a 0.22 degree tilt.
  std::vector<uint8_t> px;
  for (int i = 0; i < 4; ++i) px.insert(px.end(), {128, 128, 255});
  texture_test::write_png8(dir.file("flat.png"), 2, 2, 3, px);
  EXPECT_LT(angle_between(shade(dir.file("flat.png")), {0, 0, 1}), radians(0.5f));
}

TEST_F(NormalMapFile, TiltedMapRotatesNsByItsAngle) {
  const float t = radians(30);
  const Rgb texel = encode({0, std::sin(t), std::cos(t)});  // 30 degrees towards +v
  std::vector<float> px;
  for (int i = 0; i < 4; ++i) px.insert(px.end(), {texel.x, texel.y, texel.z});
  texture_test::write_exr(dir.file("tilted.exr"), 2, 2, 3, px);
  const Vec3f n = shade(dir.file("tilted.exr"));
  EXPECT_NEAR(angle_between(n, {0, 0, 1}), t, 1e-5f);
  EXPECT_NEAR(n.y, std::sin(t), 1e-5f);
  EXPECT_NEAR(n.x, 0, 1e-6f);
}

}  // namespace normal_map_test
}  // namespace nimbus
