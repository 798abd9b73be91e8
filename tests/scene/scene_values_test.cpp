// Good scenes: what is written lands in SceneDesc, and what is omitted keeps the documented defaults.
#include <gtest/gtest.h>

#include "scene/metals.hpp"
#include "scene_test_support.hpp"

namespace nimbus::test {
namespace scene_values_test {

TEST(SceneValues, EmptySceneUsesDefaults) {
  for (const char *text : {"", "# only a comment\n", "render:\ncamera:\nmaterials:\nobjects:\nlights:\n"}) {
    const SceneDesc scene = parse_ok(text);
    const SceneDesc defaults;
    EXPECT_EQ(scene.path, "test.yaml");
    EXPECT_EQ(scene.render.width, defaults.render.width);
    EXPECT_EQ(scene.render.integrator, "caustics");
    EXPECT_EQ(scene.render.max_depth, defaults.render.max_depth);
    EXPECT_EQ(scene.camera.position, defaults.camera.position);
    EXPECT_FLOAT_EQ(scene.camera.fov_degrees, defaults.camera.fov_degrees);
    EXPECT_TRUE(scene.materials.empty());
    EXPECT_TRUE(scene.shapes.empty());
    EXPECT_TRUE(scene.lights.empty());
  }
}

TEST(SceneValues, RenderSection) {
  const SceneDesc scene = parse_ok(R"(render:
  resolution: [640, 360]
  iterations: 256
  time: 60.5
  seed: 7
  max_depth: 12
  integrator: caustics
  caustics: on
  elements: [albedo, normal]
)");
  const RenderDesc &r = scene.render;
  EXPECT_EQ(r.width, 640u);
  EXPECT_EQ(r.height, 360u);
  EXPECT_EQ(r.iterations, 256u);
  EXPECT_DOUBLE_EQ(r.time_seconds, 60.5);
  EXPECT_EQ(r.seed, 7u);
  EXPECT_EQ(r.max_depth, 12u);
  EXPECT_EQ(r.integrator, "caustics");
  ASSERT_EQ(r.options.size(), 1u);
  EXPECT_EQ(r.options[0].name, "caustics");
  EXPECT_EQ(r.options[0].value, "on");
  EXPECT_EQ(r.elements, (std::vector<std::string>{"albedo", "normal"}));
}

TEST(SceneValues, UnknownRenderKeysAreTheIntegratorsOptionsAsWritten) {
  // The host knows no integrator option: it keeps the key, the value as written and where it was; the
  // bound integrator's declarations decide later (tests/loader/plugin_options_test.cpp, tests/e2e).
  const SceneDesc scene = parse_ok("render:\n  seed: 1\n  caustics: Off\n  photons: 12\n");
  ASSERT_EQ(scene.render.options.size(), 2u);
  EXPECT_EQ(scene.render.options[0].name, "caustics");
  EXPECT_EQ(scene.render.options[0].value, "Off");
  EXPECT_EQ(scene.render.options[0].where, "test.yaml:3:3: render.caustics");
  EXPECT_NE(scene.render.options[0].hint.find("resolution"), std::string::npos);
  EXPECT_EQ(scene.render.options[1].name, "photons");
  EXPECT_TRUE(parse_ok("render: { seed: 1 }\n").render.options.empty());
}

TEST(SceneValues, CameraSection) {
  const SceneDesc scene = parse_ok(R"(camera:
  type: perspective
  position: [0, -4, 1]
  look_at: [0, 0, 0.5]
  up: [0, 0, 1]
  fov: 40
  aperture: 0.05
  focus_distance: 4.5
)");
  const CameraDesc &c = scene.camera;
  EXPECT_EQ(c.position, Vec3f(0, -4, 1));
  EXPECT_EQ(c.look_at, Vec3f(0, 0, 0.5f));
  EXPECT_EQ(c.up, Vec3f(0, 0, 1));
  EXPECT_FLOAT_EQ(c.fov_degrees, 40);
  EXPECT_FLOAT_EQ(c.aperture, 0.05f);
  EXPECT_FLOAT_EQ(c.focus_distance, 4.5f);
}

TEST(SceneValues, Materials) {
  const SceneDesc scene = parse_ok(R"(materials:
  white: { type: diffuse, albedo: 0.5 }
  red: { type: diffuse, albedo: [0.8, 0.1, 0.1] }
  gold: { type: conductor, metal: gold, roughness: 0.05 }
  custom: { type: conductor, eta: [0.2, 0.9, 1.1], k: 3 }
  mirror: { type: conductor, reflectance: 1.0 }
  glass: { type: dielectric, ior: 1.5 }
  frosted: { type: dielectric, ior: 1.33, roughness: 0.2 }
)");
  ASSERT_EQ(scene.materials.size(), 7u);
  const auto &m = scene.materials;
  EXPECT_EQ(m[0].name, "white");
  EXPECT_EQ(m[0].type, MaterialType::Diffuse);
  EXPECT_EQ(m[0].albedo, Rgb(0.5f));
  EXPECT_EQ(m[0].where.line, 2);
  EXPECT_EQ(m[0].where.column, 10);
  EXPECT_EQ(m[1].albedo, Rgb(0.8f, 0.1f, 0.1f));

  EXPECT_EQ(m[2].type, MaterialType::Conductor);
  EXPECT_EQ(m[2].eta, find_metal("gold")->eta);
  EXPECT_EQ(m[2].k, find_metal("gold")->k);
  EXPECT_FALSE(m[2].use_reflectance);
  EXPECT_FLOAT_EQ(m[2].roughness, 0.05f);

  EXPECT_EQ(m[3].eta, Rgb(0.2f, 0.9f, 1.1f));
  EXPECT_EQ(m[3].k, Rgb(3.0f));
  EXPECT_TRUE(m[4].use_reflectance);
  EXPECT_EQ(m[4].reflectance, Rgb(1.0f));

  EXPECT_EQ(m[5].type, MaterialType::Dielectric);
  EXPECT_FLOAT_EQ(m[5].ior, 1.5f);
  EXPECT_FLOAT_EQ(m[5].roughness, 0);
  EXPECT_FLOAT_EQ(m[6].ior, 1.33f);
  EXPECT_FLOAT_EQ(m[6].roughness, 0.2f);
}

TEST(SceneValues, ObjectsReferToMaterialsByIndexWhereverMaterialsAppear) {
  // `objects:` before `materials:` in the file: references still resolve.
  const SceneDesc scene = parse_ok(R"(objects:
  - { shape: sphere, center: [1, 2, 3], radius: 0.5, material: glass }
  - shape: rectangle
    size: [2, 3]
    material: white
    emission: { radiance: [25, 20, 15] }
    two_sided: true
    group: ceiling
materials:
  white: { type: diffuse }
  glass: { type: dielectric }
)");
  ASSERT_EQ(scene.shapes.size(), 2u);
  const ShapeDesc &sphere = scene.shapes[0];
  EXPECT_EQ(sphere.type, ShapeType::Sphere);
  EXPECT_EQ(sphere.material, 1u);
  EXPECT_EQ(sphere.center, Vec3f(1, 2, 3));
  EXPECT_FLOAT_EQ(sphere.radius, 0.5f);
  EXPECT_TRUE(is_black(sphere.emission));
  EXPECT_FALSE(sphere.two_sided);
  EXPECT_EQ(sphere.where.file, "test.yaml");
  EXPECT_EQ(sphere.where.line, 2);
  EXPECT_EQ(sphere.where.column, 5);

  const ShapeDesc &light = scene.shapes[1];
  EXPECT_EQ(light.type, ShapeType::Rectangle);
  EXPECT_EQ(light.material, 0u);
  EXPECT_EQ(light.emission, Rgb(25, 20, 15));
  EXPECT_TRUE(light.two_sided);
  EXPECT_EQ(light.group, "ceiling");
  EXPECT_EQ(light.where.line, 3);
}

TEST(SceneValues, PointLights) {
  const SceneDesc scene = parse_ok(R"(lights:
  - { type: point, position: [0, -0.5, 1], intensity: [5.57, 5.57, 5.57], group: key }
  - { type: point, position: [1, 1, 1], intensity: 2 }
  - { type: point, position: [0, 0, 3] }
)");
  ASSERT_EQ(scene.lights.size(), 3u);
  EXPECT_EQ(scene.lights[0].type, LightType::Point);
  EXPECT_EQ(scene.lights[0].position, Vec3f(0, -0.5f, 1));
  EXPECT_EQ(scene.lights[0].intensity, Rgb(5.57f));
  EXPECT_EQ(scene.lights[0].group, "key");
  EXPECT_EQ(scene.lights[1].intensity, Rgb(2));
  EXPECT_EQ(scene.lights[2].intensity, LightDesc{}.intensity);
  EXPECT_EQ(scene.lights[2].where.line, 4);
}

TEST(SceneValues, SphereAndDiskDefaults) {
  const SceneDesc scene = parse_ok(R"(materials: { white: { type: diffuse } }
objects:
  - { shape: sphere, radius: 2, material: white }
  - { shape: disk, radius: 3, material: white }
)");
  ASSERT_EQ(scene.shapes.size(), 2u);
  EXPECT_EQ(scene.shapes[0].center, Vec3f(0, 0, 0));
  EXPECT_EQ(scene.shapes[1].type, ShapeType::Disk);
  EXPECT_EQ(scene.shapes[1].normal, Vec3f(0, 0, 1));
  EXPECT_FLOAT_EQ(scene.shapes[1].radius, 3);
}

TEST(SceneValues, InlineMeshFlatAndNestedIndicesAgree) {
  const std::string head = R"(materials: { white: { type: diffuse } }
objects:
  - shape: mesh
    material: white
    positions: [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]
    normals: [[0, 0, 2], [0, 0, 1], [0, 0, 1], [0, 0, 1]]
    uvs: [[0, 0], [1, 0], [1, 1], [0, 1]]
)";
  const SceneDesc flat = parse_ok(head + "    indices: [0, 1, 2, 0, 2, 3]\n");
  const SceneDesc nested = parse_ok(head + "    indices: [[0, 1, 2], [0, 2, 3]]\n");
  ASSERT_EQ(flat.shapes.size(), 1u);
  const MeshData &mesh = flat.shapes[0].mesh;
  EXPECT_EQ(mesh.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
  EXPECT_EQ(nested.shapes[0].mesh.indices, mesh.indices);
  ASSERT_EQ(mesh.positions.size(), 4u);
  ASSERT_EQ(mesh.normals.size(), 4u);
  expect_vec(mesh.normals[0], {0, 0, 1});  // normalised
  ASSERT_EQ(mesh.uvs.size(), 4u);
  EXPECT_FLOAT_EQ(mesh.uvs[2].x, 1);
  EXPECT_FLOAT_EQ(mesh.uvs[2].y, 1);
}

}  // namespace scene_values_test
}  // namespace nimbus::test
