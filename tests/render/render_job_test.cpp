// The render job: each precedence between the scene and the command line decided once (stopping rules,
// seed, filter, integrator, light sampler, elements), inconsistent requests refused before any work, and
// the checkpoint fingerprint made from every file the parser read.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "render/render_job.hpp"
#include "scene/scene_parser.hpp"

namespace nimbus {
namespace render_job_test {

SceneDesc parse(const std::string &yaml) {
  auto scene = parse_scene_string(yaml, "job.yaml");
  EXPECT_TRUE(scene.ok()) << (scene.ok() ? "" : scene.error().message);
  return scene.ok() ? std::move(scene).value() : SceneDesc{};
}

RenderJob resolve(const SceneDesc &scene, const RenderOptions &options) {
  auto job = resolve_job(scene, options);
  EXPECT_TRUE(job.ok()) << (job.ok() ? "" : job.error().message);
  return job.ok() ? std::move(job).value() : RenderJob{};
}

TEST(RenderJob, TheCommandLinesStoppingRulesReplaceTheScenes) {
  const SceneDesc scene = parse("render: { iterations: 16, time: 30 }\n");
  RenderOptions options;
  RenderJob job = resolve(scene, options);
  EXPECT_EQ(job.stop.iterations, 16u);
  EXPECT_EQ(job.stop.time_seconds, 30);
  options.time_seconds = 60;
  job = resolve(scene, options);
  EXPECT_EQ(job.stop.iterations, 0u) << "--time alone: no iteration limit";
  EXPECT_EQ(job.stop.time_seconds, 60);
  EXPECT_EQ(resolve(parse(""), {}).stop.iterations, kDefaultIterations);
  EXPECT_EQ(resolve(parse("render: { target_error: 0.01 }\n"), {}).stop.iterations, 0u);
}

TEST(RenderJob, OverridesAndTheScenesValues) {
  const SceneDesc scene = parse(
      "render: { seed: 5, filter: gaussian, integrator: caustics, light_sampler: nimbus.lights.power, "
      "elements: [albedo, lightmix] }\n");
  RenderOptions options;
  options.output_exr = "out/a.exr";
  options.elements = {"depth"};
  RenderJob job = resolve(scene, options);
  EXPECT_EQ(job.seed, 5u);
  EXPECT_EQ(job.filter, FilterType::Gaussian);
  EXPECT_EQ(job.integrator, "caustics");
  EXPECT_EQ(job.elements, (std::vector<std::string>{"albedo", "depth"}));
  EXPECT_TRUE(job.lightmix);
  EXPECT_EQ(job.light_sampler_for(100), "nimbus.lights.power");
  EXPECT_EQ(job.png_path, "out/a.png");
  EXPECT_EQ(job.checkpoint_path, "out/a.exr.ckpt");

  options.seed = 9;
  options.filter = FilterType::Box;
  options.integrator = "nimbus.pt";
  options.light_sampler = "nimbus.lights.tree";
  job = resolve(scene, options);
  EXPECT_EQ(job.seed, 9u);
  EXPECT_EQ(job.filter, FilterType::Box);
  EXPECT_EQ(job.integrator, "nimbus.pt");
  EXPECT_EQ(job.light_sampler_for(1), "nimbus.lights.tree");
}

TEST(RenderJob, TheLightSamplerFollowsTheLightCountUnlessNamed) {
  const RenderJob job = resolve(parse(""), {});
  EXPECT_EQ(job.light_sampler_for(kTreeLightThreshold), "nimbus.lights.power");
  EXPECT_EQ(job.light_sampler_for(kTreeLightThreshold + 1), "nimbus.lights.tree");
}

TEST(RenderJob, AnErrorTargetCannotResume) {
  RenderOptions options;
  options.resume = true;
  options.target_error = 0.01;
  const SceneDesc scene = parse("");
  const auto job = resolve_job(scene, options);
  ASSERT_FALSE(job.ok());
  EXPECT_NE(job.error().message.find("cannot resume a checkpoint"), std::string::npos) << job.error().message;
}

// Without other files, the lines are those checkpoints have always held.
TEST(RenderJob, FingerprintOfASceneWithoutOtherFiles) {
  const SceneDesc scene = parse("render: { resolution: [8, 4], seed: 3, caustics: on }\n");
  RenderOptions options;
  options.elements = {"albedo"};
  const RenderJob job = resolve(scene, options);
  EXPECT_EQ(job.fingerprint("nimbus.caustics", "nimbus.lights.power", {{"caustics", "on"}}),
            "scene_hash=" + scene.sources.at(0).hash +
                "\nresolution=8x4\nregion=0,0,0,0\nseed=3\nintegrator=nimbus.caustics\n"
                "light_sampler=nimbus.lights.power\nfilter=box\nmax_depth=16\noptions=caustics:on\n"
                "elements=albedo\n");
}

TEST(RenderJob, FingerprintCoversIncludedFilesAndMeshes) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("nimbus-job-test-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir / "parts");
  const auto write = [&](const std::string &name, const std::string &text) {
    std::ofstream(dir / name) << text;
  };
  write("main.yaml", "include: parts/room.yaml\n");
  write("parts/room.yaml",
        "materials:\n  m: { type: diffuse }\nobjects:\n  - { shape: mesh, file: quad.obj, material: m }\n");
  write("parts/quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n");
  const auto fingerprint = [&] {
    const auto scene = parse_scene_file((dir / "main.yaml").string());
    EXPECT_TRUE(scene.ok()) << (scene.ok() ? "" : scene.error().message);
    return scene.ok() ? resolve(scene.value(), {}).fingerprint("nimbus.pt", "nimbus.lights.power", {}) : "";
  };
  const std::string before = fingerprint();
  EXPECT_NE(before.find("\nfile:parts/room.yaml="), std::string::npos) << before;
  EXPECT_NE(before.find("\nfile:parts/quad.obj="), std::string::npos) << before;
  write("parts/quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 3 2\n");
  const std::string after = fingerprint();
  EXPECT_NE(before, after) << "an edited mesh is a different render";
  std::filesystem::remove_all(dir);
}

}  // namespace render_job_test
}  // namespace nimbus
