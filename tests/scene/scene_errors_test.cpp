// Bad scenes: each error names the exact line:column, the key path and the problem, on one line.
#include <gtest/gtest.h>

#include "scene_test_support.hpp"

namespace nimbus::test {
namespace scene_errors_test {

// Lines 1-2 of most object tests, so that `objects:` is line 3 and the first object starts at 4:5.
const std::string kWhite = "materials:\n  white: { type: diffuse }\n";

TEST(SceneErrors, YamlSyntaxError) {
  EXPECT_TRUE(fails_at("render:\n  seed: 1\n    max_depth: 4\n", 3, 14, "YAML syntax", "illegal map value"));
}

TEST(SceneErrors, UnclosedFlowSequence) {
  EXPECT_TRUE(
      fails_at("render:\n  resolution: [640, 360\n  seed: 1\n", 3, 7, "YAML syntax", "end of sequence"));
}

TEST(SceneErrors, UnknownTopLevelKey) {
  EXPECT_TRUE(fails_at("render:\n  seed: 1\ntextures: { wood: wood.png }\n", 3, 1, "textures",
                       "unknown key 'textures'; allowed: render, camera, materials, meshes, objects, lights, "
                       "environment, include"));
}

TEST(SceneErrors, StrayFlowIndicator) {
  // yaml-cpp 0.7 would loop forever on these (LoadAll) or accept them as an empty scene (Load).
  EXPECT_TRUE(fails_at(",\n", 1, 1, "YAML syntax", "unexpected ','"));
  EXPECT_TRUE(fails_at("render: { seed: 1 }\n...\n, camera: {}\n", 3, 1, "YAML syntax", "unexpected ','"));
}

TEST(SceneErrors, TopLevelMustBeAMap) {
  EXPECT_TRUE(fails_at("- render\n- camera\n", 1, 1, "scene", "expected a map of sections, got a sequence"));
}

TEST(SceneErrors, SecondYamlDocument) {
  EXPECT_TRUE(
      fails_at("render: { seed: 1 }\n---\ncamera: { fov: 30 }\n", 2, 1, "scene", "one YAML document"));
}

// Unknown render keys are the integrator's options, checked once it is bound
// (tests/e2e/integrator_options_test.cpp); a value that is no scalar is wrong for any option.
TEST(SceneErrors, IntegratorOptionNeedsAValue) {
  EXPECT_TRUE(fails_at("render:\n  resolution: [64, 64]\n  photons: [1, 2]\n", 3, 12, "render.photons",
                       "expected a value for the integrator's option, got a sequence"));
}

TEST(SceneErrors, LongUserTextIsAbbreviated) {
  const std::string key(60, 'x'), shown = std::string(40, 'x') + "...";
  EXPECT_TRUE(
      fails_at("camera:\n  " + key + ": 1\n", 2, 3, "camera." + shown, "unknown key '" + shown + "'"));
}

TEST(SceneErrors, UnknownCameraKey) {
  EXPECT_TRUE(fails_at("camera:\n  fov: 40\n  lens: 35\n", 3, 3, "camera.lens", "unknown key 'lens'"));
}

TEST(SceneErrors, UnknownCameraType) {
  EXPECT_TRUE(fails_at("camera:\n  type: orthographic\n", 2, 9, "camera.type",
                       "unknown camera type 'orthographic'; supported: perspective"));
}

TEST(SceneErrors, UnknownMaterialKeyForItsType) {
  EXPECT_TRUE(fails_at("materials:\n  white:\n    type: diffuse\n    ior: 1.5\n", 4, 5, "materials.white.ior",
                       "unknown key 'ior' for a diffuse material; allowed: type, albedo"));
}

TEST(SceneErrors, UnknownObjectKeyForItsShape) {
  EXPECT_TRUE(
      fails_at(kWhite + "objects:\n  - shape: sphere\n    radius: 1\n    material: white\n    size: 2\n", 7,
               5, "objects[0].size", "unknown key 'size' for a sphere"));
}

TEST(SceneErrors, UnknownLightKey) {
  EXPECT_TRUE(fails_at("lights:\n  - { type: point, position: [0, 0, 1], cone: 30 }\n", 2, 41,
                       "lights[0].cone", "unknown key 'cone' for a point light"));
}

TEST(SceneErrors, NumberExpectedGotString) {
  EXPECT_TRUE(fails_at(kWhite + "objects:\n  - shape: sphere\n    radius: abc\n    material: white\n", 5, 13,
                       "objects[0].radius", "expected a number, got 'abc'"));
}

TEST(SceneErrors, QuotedNumberIsAString) {
  EXPECT_TRUE(fails_at(kWhite + "objects:\n  - shape: sphere\n    radius: \"1\"\n    material: white\n", 5,
                       13, "objects[0].radius", "expected a number, got the string \"1\""));
}

TEST(SceneErrors, NumberExpectedGotSequence) {
  EXPECT_TRUE(fails_at("camera:\n  fov: [40]\n", 2, 8, "camera.fov", "expected a number, got a sequence"));
}

TEST(SceneErrors, EmptyValueIsReportedAtItsKey) {
  EXPECT_TRUE(fails_at(kWhite + "objects:\n  - shape: sphere\n    radius:\n    material: white\n", 5, 5,
                       "objects[0].radius", "expected a number, got null"));
}

TEST(SceneErrors, NonFiniteNumber) {
  EXPECT_TRUE(fails_at("camera:\n  aperture: .inf\n", 2, 13, "camera.aperture",
                       "must be a finite number (got .inf)"));
}

TEST(SceneErrors, WrongVectorLength) {
  EXPECT_TRUE(fails_at(
      kWhite + "objects:\n  - shape: sphere\n    center: [0, 0]\n    radius: 1\n    material: white\n", 5, 13,
      "objects[0].center", "expected [x, y, z] (3 elements), got 2 elements"));
}

TEST(SceneErrors, VectorElementOfWrongType) {
  EXPECT_TRUE(fails_at("camera:\n  position: [0, zero, 1]\n", 2, 17, "camera.position[1]",
                       "expected a number, got 'zero'"));
}

TEST(SceneErrors, NegativeRadius) {
  EXPECT_TRUE(fails_at(kWhite + "objects:\n  - shape: sphere\n    radius: -1\n    material: white\n", 5, 13,
                       "objects[0].radius", "must be > 0 (got -1)"));
}

TEST(SceneErrors, FovOutOfRange) {
  EXPECT_TRUE(fails_at("camera:\n  fov: 180\n", 2, 8, "camera.fov", "must be in (0, 180) (got 180)"));
}

TEST(SceneErrors, ZeroResolution) {
  EXPECT_TRUE(fails_at("render:\n  resolution: [0, 360]\n", 2, 16, "render.resolution[0]",
                       "must be in [1, 16384] (got 0)"));
}

TEST(SceneErrors, ResolutionNeedsIntegers) {
  EXPECT_TRUE(fails_at("render:\n  resolution: [640, 360.5]\n", 2, 21, "render.resolution[1]",
                       "expected an integer, got 360.5"));
}

TEST(SceneErrors, ResolutionNeedsTwoElements) {
  EXPECT_TRUE(fails_at("render:\n  resolution: [640, 360, 3]\n", 2, 15, "render.resolution",
                       "expected [width, height] (2 elements), got 3 elements"));
}

TEST(SceneErrors, RenderCountsOutOfRange) {
  EXPECT_TRUE(fails_at("render:\n  iterations: 0\n", 2, 15, "render.iterations", "must be >= 1 (got 0)"));
  EXPECT_TRUE(
      fails_at("render:\n  max_depth: 2000\n", 2, 14, "render.max_depth", "must be in [1, 1024] (got 2000)"));
  EXPECT_TRUE(fails_at("render:\n  seed: -3\n", 2, 9, "render.seed", "must be >= 0 (got -3)"));
  EXPECT_TRUE(fails_at("render:\n  time: 0\n", 2, 9, "render.time", "must be > 0 (got 0)"));
}

TEST(SceneErrors, ElementListedTwice) {
  EXPECT_TRUE(fails_at("render:\n  elements: [albedo, normal, albedo]\n", 2, 30, "render.elements[2]",
                       "element 'albedo' is listed twice"));
}

TEST(SceneErrors, DuplicateKey) {
  EXPECT_TRUE(fails_at("camera:\n  fov: 40\n  fov: 50\n", 3, 3, "camera.fov",
                       "duplicate key 'fov' (first at line 2, column 3)"));
}

TEST(SceneErrors, DegenerateCamera) {
  EXPECT_TRUE(fails_at("camera:\n  position: [1, 2, 3]\n  look_at: [1, 2, 3]\n", 3, 12, "camera.look_at",
                       "look_at equals position"));
  EXPECT_TRUE(fails_at("camera:\n  position: [0, 0, 5]\n  look_at: [0, 0, 0]\n  up: [0, 0, 1]\n", 4, 7,
                       "camera.up", "up is parallel to the viewing direction"));
}

TEST(SceneErrors, UnknownMaterialReference) {
  EXPECT_TRUE(fails_at(kWhite + "objects:\n  - shape: sphere\n    radius: 1\n    material: glas\n", 6, 15,
                       "objects[0].material", "unknown material 'glas'; defined: white"));
}

TEST(SceneErrors, UnknownShape) {
  EXPECT_TRUE(
      fails_at(kWhite + "objects:\n  - shape: cylinder\n    material: white\n", 4, 12, "objects[0].shape",
               "unknown shape 'cylinder'; known: sphere, rectangle, box, disk, mesh, instance, subdivision"));
}

TEST(SceneErrors, UnknownMaterialType) {
  EXPECT_TRUE(fails_at("materials:\n  shiny:\n    type: plastic\n", 3, 11, "materials.shiny.type",
                       "unknown material type 'plastic'; known: diffuse, conductor, dielectric"));
}

TEST(SceneErrors, UnknownMetalListsKnownOnes) {
  EXPECT_TRUE(fails_at("materials:\n  m:\n    type: conductor\n    metal: platinum\n", 4, 12,
                       "materials.m.metal",
                       "unknown metal 'platinum'; known: gold, silver, copper, aluminium, aluminum"));
}

TEST(SceneErrors, ConductorDescribedTwoWays) {
  EXPECT_TRUE(fails_at("materials:\n  m:\n    type: conductor\n    metal: gold\n    eta: 0.2\n    k: 3\n", 5,
                       5, "materials.m.eta", "conflicts with 'metal'"));
}

TEST(SceneErrors, ConductorEtaWithoutK) {
  EXPECT_TRUE(fails_at("materials:\n  m:\n    type: conductor\n    eta: [0.2, 0.9, 1.1]\n", 3, 5,
                       "materials.m.k", "missing required key 'k'"));
}

TEST(SceneErrors, AlbedoComponentOutOfRange) {
  EXPECT_TRUE(fails_at("materials:\n  red:\n    type: diffuse\n    albedo: [0.5, 1.5, 0.5]\n", 4, 19,
                       "materials.red.albedo[1]", "must be in [0, 1] (got 1.5)"));
}

TEST(SceneErrors, IorBelowOne) {
  EXPECT_TRUE(fails_at("materials:\n  glass: { type: dielectric, ior: 0.5 }\n", 2, 35, "materials.glass.ior",
                       "must be in [1, 10] (got 0.5)"));
}

TEST(SceneErrors, MissingRequiredKeyReportedAtTheMap) {
  EXPECT_TRUE(fails_at(kWhite + "objects:\n  - shape: sphere\n    material: white\n", 4, 5,
                       "objects[0].radius", "missing required key 'radius'"));
  EXPECT_TRUE(fails_at(kWhite + "objects:\n  - { radius: 1, material: white }\n", 4, 5, "objects[0].shape",
                       "missing required key 'shape'"));
}

TEST(SceneErrors, NegativeEmission) {
  EXPECT_TRUE(fails_at(kWhite + "objects:\n  - shape: disk\n    radius: 1\n    material: white\n"
                                "    emission: { radiance: [1, -1, 1] }\n",
                       7, 31, "objects[0].emission.radiance[1]", "must be >= 0 (got -1)"));
}

TEST(SceneErrors, NonUniformScaleOnSphere) {
  EXPECT_TRUE(fails_at(kWhite + "objects:\n  - shape: sphere\n    radius: 1\n    material: white\n"
                                "    transform: { scale: [1, 2, 1] }\n",
                       7, 16, "objects[0].transform",
                       "a sphere allows only rotation, translation and uniform scale (axis scales 1, 2, 1)"));
}

TEST(SceneErrors, NonUniformScaleOnDisk) {
  EXPECT_TRUE(fails_at(kWhite + "objects:\n  - shape: disk\n    radius: 1\n    material: white\n"
                                "    transform: { rotate: [0, 30, 0], scale: [3, 1, 1] }\n",
                       7, 16, "objects[0].transform", "a disk allows only rotation"));
}

TEST(SceneErrors, ZeroScale) {
  EXPECT_TRUE(fails_at(kWhite + "objects:\n  - shape: box\n    size: [1, 1, 1]\n    material: white\n"
                                "    transform: { scale: [1, 0, 1] }\n",
                       7, 29, "objects[0].transform.scale[1]", "must not be 0"));
}

TEST(SceneErrors, MatrixCombinedWithTranslate) {
  EXPECT_TRUE(fails_at(kWhite +
                           "objects:\n  - shape: box\n    size: [1, 1, 1]\n    material: white\n"
                           "    transform:\n      matrix: [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]\n"
                           "      translate: [1, 2, 3]\n",
                       9, 7, "objects[0].transform.translate", "cannot be combined with 'matrix'"));
}

TEST(SceneErrors, MatrixWithFifteenNumbers) {
  EXPECT_TRUE(fails_at(kWhite + "objects:\n  - shape: box\n    size: [1, 1, 1]\n    material: white\n"
                                "    transform: { matrix: [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0] }\n",
                       7, 26, "objects[0].transform.matrix",
                       "expected 16 numbers, row-major (16 elements), got 15"));
}

TEST(SceneErrors, RotationOfWrongShape) {
  EXPECT_TRUE(fails_at(kWhite + "objects:\n  - shape: box\n    size: [1, 1, 1]\n    material: white\n"
                                "    transform: { rotate: [[0, 0, 1]] }\n",
                       7, 27, "objects[0].transform.rotate[0]",
                       "expected [axis_x, axis_y, axis_z, degrees]"));
}

TEST(SceneErrors, MeshIndexOutOfRange) {
  EXPECT_TRUE(
      fails_at(kWhite + "objects:\n  - shape: mesh\n    material: white\n"
                        "    positions: [[0, 0, 0], [1, 0, 0], [0, 1, 0]]\n    indices: [0, 1, 2, 0, 2, 3]\n",
               7, 30, "objects[0].indices[5]", "vertex index 3 is out of range: the mesh has 3 positions"));
}

TEST(SceneErrors, MeshIndicesNotTriangles) {
  EXPECT_TRUE(fails_at(kWhite +
                           "objects:\n  - shape: mesh\n    material: white\n"
                           "    positions: [[0, 0, 0], [1, 0, 0], [0, 1, 0]]\n    indices: [0, 1, 2, 0]\n",
                       7, 14, "objects[0].indices", "expected 3 indices per triangle, got 4 indices"));
}

TEST(SceneErrors, MeshNormalsCountMismatch) {
  EXPECT_TRUE(fails_at(kWhite + "objects:\n  - shape: mesh\n    material: white\n"
                                "    positions: [[0, 0, 0], [1, 0, 0], [0, 1, 0]]\n    indices: [[0, 1, 2]]\n"
                                "    normals: [[0, 0, 1], [0, 0, 1]]\n",
                       8, 14, "objects[0].normals", "has 2 normals but the mesh has 3 positions"));
}

TEST(SceneErrors, MeshWithoutGeometry) {
  EXPECT_TRUE(fails_at(kWhite + "objects:\n  - { shape: mesh, material: white }\n", 4, 5, "objects[0]",
                       "a mesh needs 'file', or 'positions' and 'indices'"));
}

TEST(SceneErrors, UnknownLightType) {
  EXPECT_TRUE(fails_at("lights:\n  - type: area\n    position: [0, 0, 1]\n", 2, 11, "lights[0].type",
                       "unknown light type 'area'; known: point, spot, sun"));
}

TEST(SceneErrors, LightWithoutPosition) {
  EXPECT_TRUE(fails_at("lights:\n  - type: point\n    intensity: 5\n", 2, 5, "lights[0].position",
                       "missing required key 'position'"));
}

TEST(SceneErrors, ObjectsMustBeAList) {
  EXPECT_TRUE(fails_at(kWhite + "objects:\n  ball: { shape: sphere }\n", 4, 3, "objects",
                       "expected a sequence, got a map"));
}

TEST(SceneErrors, TwoSidedNeedsABoolean) {
  EXPECT_TRUE(
      fails_at(kWhite + "objects:\n  - { shape: disk, radius: 1, material: white, two_sided: sometimes }\n",
               4, 59, "objects[0].two_sided", "expected true or false, got 'sometimes'"));
}

TEST(SceneErrors, SceneFileThatDoesNotExist) {
  const std::string path = kFixtures + "/no_such_scene.yaml";
  const Expected<SceneDesc> scene = parse_scene_file(path);
  ASSERT_FALSE(scene.ok());
  EXPECT_EQ(scene.error().message, path + ": error: cannot read scene file: No such file or directory");
}

TEST(SceneErrors, MissingObjFileNamesPathAndReason) {
  const std::string scene_path = kFixtures + "/missing_mesh_scene.yaml";
  EXPECT_TRUE(error_is(parse_scene_file(scene_path), scene_path, 6, 11, "objects[0].file",
                       "cannot load mesh '" + kFixtures + "/meshes/missing.obj': No such file or directory"));
}

TEST(SceneErrors, MalformedObjFile) {
  const std::string obj = kFixtures + "/meshes/malformed.obj";
  EXPECT_TRUE(fails_at(kWhite + "objects:\n  - { shape: mesh, material: white, file: " + obj + " }\n", 4, 43,
                       "objects[0].file",
                       "cannot load mesh '" + obj + "': malformed OBJ: Failed parse `f' line"));
}

TEST(SceneErrors, ObjFaceIndexOutOfRange) {
  const std::string obj = kFixtures + "/meshes/bad_index.obj";
  EXPECT_TRUE(fails_at(kWhite + "objects:\n  - { shape: mesh, material: white, file: " + obj + " }\n", 4, 43,
                       "objects[0].file", "face 1 refers to vertex 9 but the file has 3"));
}

}  // namespace scene_errors_test
}  // namespace nimbus::test
