// The frozen 1.0 fixtures (sdk-idioms.md §4.1) loaded by the current host through the real CLI, found
// through NIMBUS_PLUGIN_PATH as a third-party plugin would be.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "abi_test_support.hpp"

namespace nimbus::abi_test {
namespace frozen_cli_test {

const char *const kFixtureIds[] = {"org.nimbus.abi.direct", "org.nimbus.abi.uniform",
                                   "org.nimbus.abi.cpp.constant", "org.nimbus.abi.cpp.guide"};

TEST(FrozenAbi10Cli, PluginsListsEveryFixtureAsLoaded) {
  ScratchDir dir;
  const RunResult r = run_with_plugin_path({NIMBUS_CLI, "plugins"}, fixture_dir(), dir.path());
  ASSERT_NE(r.exit_code, -1) << r.err;
  for (const char *id : kFixtureIds) {
    bool found = false;
    std::istringstream lines(r.out);
    for (std::string line; std::getline(lines, line);) {
      if (line.rfind(std::string(id) + " ", 0) != 0) continue;
      found = true;
      EXPECT_NE(line.find(" loaded "), std::string::npos) << line;
      EXPECT_NE(line.find(fixture_dir()), std::string::npos) << line;
    }
    EXPECT_TRUE(found) << id << " not listed:\n" << r.out << r.err;
  }
}

TEST(FrozenAbi10Cli, DirectIntegratorMatchesTheReference) {
  ScratchDir dir;
  const std::string out = dir.file("direct.exr");
  const RunResult r =
      run_with_plugin_path({NIMBUS_CLI, "render", scene_path(), "-o", out, "--elements", "caustics", "-q"},
                           fixture_dir(), dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto img = read_exr_layers(out);
  ASSERT_TRUE(img) << img.error().message;
  expect_finite_layer(img.value(), "beauty");
  expect_finite_layer(img.value(), "caustics");
  EXPECT_GT(layer_mean(img.value(), "beauty"), 0.0);
  for (float v : img.value().layers["caustics"].data)
    ASSERT_EQ(v, 0.0f) << "the fixture writes zero caustics";
  EXPECT_EQ(img.value().strings["nimbus:integrator"], "org.nimbus.abi.direct");
  EXPECT_EQ(img.value().numbers["nimbus:iterations"], 4.0);

  if (updating_reference()) {
    std::filesystem::copy_file(out, reference_path(), std::filesystem::copy_options::overwrite_existing);
    GTEST_SKIP() << "wrote " << reference_path();
  }
  auto ref = read_exr_layers(reference_path());
  ASSERT_TRUE(ref) << ref.error().message;
  for (const char *layer : {"beauty", "caustics"})
    EXPECT_LE(relative_rmse(img.value(), ref.value(), layer), kReferenceTolerance)
        << layer << " differs from " << reference_path()
        << ". If the host's transport changed on purpose (not its ABI), regenerate the reference with "
           "NIMBUS_ABI_UPDATE_REFERENCE=1 and say why in the commit.";
}

TEST(FrozenAbi10Cli, UniformSamplerRendersTheReference) {
  ScratchDir dir;
  const std::string out = dir.file("uniform.exr");
  const RunResult r = run_with_plugin_path({NIMBUS_CLI, "render", scene_path(), "-o", out, "--elements",
                                            "caustics", "--light-sampler", "org.nimbus.abi.uniform", "-q"},
                                           fixture_dir(), dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto img = read_exr_layers(out);
  ASSERT_TRUE(img) << img.error().message;
  EXPECT_EQ(img.value().strings["nimbus:light_sampler"], "org.nimbus.abi.uniform");
  expect_finite_layer(img.value(), "beauty");
  expect_finite_layer(img.value(), "caustics");
  // One light: uniform and power-proportional picking are the same distribution, so the image rendered
  // with the host's default sampler is the reference here too.
  auto ref = read_exr_layers(reference_path());
  ASSERT_TRUE(ref) << ref.error().message;
  EXPECT_LE(relative_rmse(img.value(), ref.value(), "beauty"), kReferenceTolerance);
}

TEST(FrozenAbi10Cli, WrapperIntegratorRendersItsConstant) {
  ScratchDir dir;
  const std::string out = dir.file("constant.exr");
  const RunResult r = run_with_plugin_path({NIMBUS_CLI, "render", scene_path(), "-o", out, "--integrator",
                                            "org.nimbus.abi.cpp.constant", "--iterations", "2", "-q"},
                                           fixture_dir(), dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto img = read_exr_layers(out);
  ASSERT_TRUE(img) << img.error().message;
  expect_finite_layer(img.value(), "beauty");
  const std::vector<float> &px = img.value().layers["beauty"].data;
  const float want[3] = {0.25f, 0.5f, 0.75f};
  for (size_t i = 0; i < px.size(); ++i) ASSERT_NEAR(px[i], want[i % 3], 1e-6) << "value " << i;
}

// Renders `scene` (written to a file) with the 1.0 direct integrator: refused, exit code 1, with the
// error `where` (a position in the file) followed by `error`, and no image written.
void expect_refused(const std::string &scene, const std::string &where, const std::string &error) {
  ScratchDir dir;
  const std::string path = dir.file("scene.yaml"), out = dir.file("x.exr");
  std::ofstream(path) << "render: { resolution: [16, 16], integrator: org.nimbus.abi.direct }\n" << scene;
  const RunResult r =
      run_with_plugin_path({NIMBUS_CLI, "render", path, "-q", "-o", out}, fixture_dir(), dir.path());
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find(path + ":" + where + ": " + error), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out));
}

// A scene that moves needs an integrator that gives its paths times (the "motion-blur" feature, SDK
// 1.7): a 1.0 integrator is refused before rendering, naming what moves, rather than rendering it frozen.
TEST(FrozenAbi10Cli, MovingSceneIsRefusedToAnIntegratorWithoutMotionBlur) {
  expect_refused(
      "camera: { position: [0, -5, 1], look_at: [0, 0, 0.5], shutter: { open: 0, close: 1 } }\n"
      "materials: { white: { type: diffuse } }\n"
      "objects:\n"
      "  - { shape: rectangle, size: [10, 10], material: white }\n"
      "  - shape: box\n"
      "    size: [1, 1, 1]\n"
      "    material: white\n"
      "    motion: [{ time: 0, translate: [0, 0, 0.5] }, { time: 1, translate: [1, 0, 0.5] }]\n"
      "lights: [{ type: point, position: [0, 0, 4], power: 100 }]\n",
      "6:5", "motion: integrator 'org.nimbus.abi.direct' does not render motion blur");
}

// A dispersive glass needs an integrator that gives its paths wavelengths (the "dispersion" feature, SDK
// 1.7): a 1.0 integrator is refused, naming the material, rather than rendering the glass without a
// rainbow.
TEST(FrozenAbi10Cli, DispersiveSceneIsRefusedToAnIntegratorWithoutDispersion) {
  expect_refused(
      "materials:\n"
      "  white: { type: diffuse }\n"
      "  flint: { type: dielectric, ior: 1.75, abbe: 25 }\n"
      "objects:\n"
      "  - { shape: rectangle, size: [10, 10], material: white }\n"
      "  - { shape: sphere, radius: 0.5, center: [0, 0, 0.5], material: flint }\n"
      "lights: [{ type: point, position: [0, 0, 4], power: 100 }]\n",
      "4:10", "integrator 'org.nimbus.abi.direct' does not render dispersion");
}

}  // namespace frozen_cli_test
}  // namespace nimbus::abi_test
