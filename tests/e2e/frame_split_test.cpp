// One frame shared between processes: `nimbus render --task K --tasks N` renders the frame-wide iterations
// K + 1 + k N into a partial EXR, and `nimbus merge` joins the parts into the image one render of all their
// iterations makes. Path tracing (the caustics solver switched off) draws its camera samples from (seed,
// pixel, frame iteration) alone, so its merged parts are the whole render's sums; the caustics solver
// adapts within each task, so its merge is
// compared statistically with a whole render. Refusals (other frames, overlaps, missing tasks) name the
// files.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <string>
#include <vector>

#include "e2e_support.hpp"
#include "support/render_support.hpp"

namespace nimbus::e2e {
namespace frame_split_test {

// scenes/split_sphere.yaml: a small glass sphere's caustic under a point light, with the caustics element
// and a LightMix layer for each of its two lights.
std::string split_scene() { return scene("split_sphere.yaml"); }

// Renders `scene` with `extra` arguments into `out`; records a failure when it does not exit 0.
bool render(const TestDir &dir, const std::string &scene, const std::string &out,
            const std::vector<std::string> &extra) {
  std::vector<std::string> args = {"render", scene, "-o", out, "-q", "--threads", "2"};
  args.insert(args.end(), extra.begin(), extra.end());
  const ProcessResult r = run_nimbus(args, dir);
  if (!exited_with(r, 0)) ADD_FAILURE() << r.describe();
  return exited_with(r, 0);
}

// Renders the N parts of `scene` (iterations as the scene or `extra` say) and returns their paths.
std::vector<std::string> render_parts(const TestDir &dir, const std::string &scene, uint32_t tasks,
                                      const std::vector<std::string> &extra,
                                      const std::string &stem = "part") {
  std::vector<std::string> parts;
  for (uint32_t k = 0; k < tasks; ++k) {
    parts.push_back(dir.file(stem + std::to_string(k) + ".exr"));
    std::vector<std::string> args = {"--task", std::to_string(k), "--tasks", std::to_string(tasks)};
    args.insert(args.end(), extra.begin(), extra.end());
    render(dir, scene, parts.back(), args);
  }
  return parts;
}

ProcessResult merge(const TestDir &dir, std::vector<std::string> parts, const std::string &out,
                    const std::vector<std::string> &extra = {}) {
  std::vector<std::string> args = {"merge"};
  args.insert(args.end(), parts.begin(), parts.end());
  args.insert(args.end(), {"-o", out});
  args.insert(args.end(), extra.begin(), extra.end());
  return run_nimbus(args, dir);
}

TEST(FrameSplit, PathTracerPartsMergeToTheWholeRenderBitForBit) {
  TestDir dir;
  const std::string scene = split_scene();
  const std::vector<std::string> pt = {"--caustics", "off", "--iterations", "10"};
  ASSERT_TRUE(render(dir, scene, dir.file("whole.exr"), pt));
  // 10 iterations over 4 tasks: 3, 3, 2 and 2 of them, in reverse order on the command line.
  std::vector<std::string> parts = render_parts(dir, scene, 4, pt);
  std::reverse(parts.begin(), parts.end());
  const ProcessResult m = merge(dir, parts, dir.file("merged.exr"));
  ASSERT_TRUE(exited_with(m, 0)) << m.describe();
  const auto whole = read_exr(dir.file("whole.exr")), merged = read_exr(dir.file("merged.exr"));
  const auto part = read_exr(dir.file("part3.exr"));
  ASSERT_TRUE(whole && merged && part);
  EXPECT_EQ(meta_number(*part, "nimbus:iterations"), 2.0);
  EXPECT_EQ(meta_number(*merged, "nimbus:iterations"), 10.0);
  EXPECT_EQ(meta_number(*merged, "nimbus:tasks_merged"), 4.0);
  EXPECT_TRUE(std::filesystem::exists(dir.file("merged.png")));
  EXPECT_FALSE(std::filesystem::exists(dir.file("part0.png"))) << "a part has no preview";
  // Every element, LightMix layers included, is the whole render's to the bit: float samples summed in
  // double are exact at these magnitudes, whatever the grouping.
  ASSERT_EQ(whole->channels.size(), merged->channels.size());
  for (const auto &[name, plane] : whole->channels) {
    ASSERT_TRUE(merged->channels.count(name)) << name;
    const std::vector<float> &other = merged->channels.at(name);
    size_t differ = 0;
    for (size_t i = 0; i < plane.size(); ++i)
      differ += std::bit_cast<uint32_t>(plane[i]) != std::bit_cast<uint32_t>(other[i]);
    EXPECT_EQ(differ, 0u) << name;
  }
  EXPECT_TRUE(merged->channels.count("lightmix.key.R") && merged->channels.count("lightmix.fill.R"));
}

// The caustics solver's photon passes are numbered frame-wide (task K's pass j is the frame's K + 1 +
// (j - 1) N), so the tasks trace different photons and shrink their radii as one render does. Its merge
// is then as far from an independent render (another seed) as a whole render is. A few fireflies carry a
// third of either comparison's relMSE (10 of 5184 pixels), so each pixel's term is capped at 1 (a
// relative error of 100 %); the ratio of the two capped figures then has a spread of a few percent
// (measured 0.94), and 1.3 is far outside it for a correct merge, while a merge of correlated parts
// (every task tracing the same photons) lies towards one part alone, 2.1x the whole's.
TEST(FrameSplit, CausticsSolverMergeIsAsCloseToAnIndependentRenderAsAWholeRender) {
  TestDir dir;
  const std::string scene = split_scene();
  ASSERT_TRUE(render(dir, scene, dir.file("whole.exr"), {}));
  ASSERT_TRUE(render(dir, scene, dir.file("other.exr"), {"--seed", "2"}));
  const std::vector<std::string> parts = render_parts(dir, scene, 4, {});
  const ProcessResult m = merge(dir, parts, dir.file("merged.exr"));
  ASSERT_TRUE(exited_with(m, 0)) << m.describe();
  const auto whole = read_exr(dir.file("whole.exr")), other = read_exr(dir.file("other.exr"));
  const auto merged = read_exr(dir.file("merged.exr"));
  ASSERT_TRUE(whole && other && merged);
  for (const char *layer : {"caustics", "lightmix.key", "lightmix.fill"})
    EXPECT_TRUE(merged->layers.count(layer)) << layer;
  EXPECT_EQ(meta_number(*merged, "nimbus:iterations"), 32.0);
  const std::vector<float> &ref = other->layers.at("beauty").data;
  const double e_whole = testing::rel_mse(whole->layers.at("beauty").data, ref, 1.0);
  const double e_merged = testing::rel_mse(merged->layers.at("beauty").data, ref, 1.0);
  EXPECT_LT(e_merged, 1.3 * e_whole) << "relMSE against seed 2: merged " << e_merged << ", whole " << e_whole;
  EXPECT_GT(e_merged, e_whole / 1.3) << "merged " << e_merged << ", whole " << e_whole;
  // The caustics element carries photon light: the parts' photons really were merged.
  double caustic = 0;
  for (float v : merged->layers.at("caustics").data) caustic += v;
  EXPECT_GT(caustic, 0);
}

TEST(FrameSplit, MergeRefusesPartsOfOtherFramesOverlapsAndMissingTasks) {
  TestDir dir;
  const std::string scene = split_scene();
  const std::vector<std::string> pt = {"--caustics", "off", "--iterations", "4"};
  const std::vector<std::string> parts = render_parts(dir, scene, 3, pt);
  std::vector<std::string> seed2 = pt;
  seed2.insert(seed2.end(), {"--seed", "2"});
  const std::vector<std::string> other = render_parts(dir, scene, 3, seed2, "other");
  ASSERT_TRUE(render(dir, scene, dir.file("whole.exr"), pt));

  ProcessResult r = merge(dir, {parts[0], other[1]}, dir.file("m.exr"));
  EXPECT_TRUE(exited_with(r, 1)) << r.describe();
  EXPECT_NE(r.err.find("not parts of one frame: their seed differs"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(other[1]), std::string::npos) << r.err;

  r = merge(dir, {parts[0], parts[1], parts[1]}, dir.file("m.exr"));
  EXPECT_TRUE(exited_with(r, 1)) << r.describe();
  EXPECT_NE(r.err.find("overlap: both hold task 1 of 3"), std::string::npos) << r.err;

  r = merge(dir, {parts[0], dir.file("whole.exr")}, dir.file("m.exr"));
  EXPECT_TRUE(exited_with(r, 1)) << r.describe();
  EXPECT_NE(r.err.find("is not a part of a shared frame"), std::string::npos) << r.err;

  r = merge(dir, {parts[0], parts[2]}, dir.file("m.exr"));
  EXPECT_TRUE(exited_with(r, 1)) << r.describe();
  EXPECT_NE(r.err.find("task 1 of 3 missing"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("m.exr")));

  r = merge(dir, {parts[0], parts[2]}, dir.file("m.exr"), {"--allow-incomplete"});
  ASSERT_TRUE(exited_with(r, 0)) << r.describe();
  const auto m = read_exr(dir.file("m.exr"));
  ASSERT_TRUE(m);
  EXPECT_EQ(meta_string(*m, "nimbus:incomplete"), "tasks 1 of 3 missing");
  EXPECT_EQ(meta_number(*m, "nimbus:iterations"), 3.0);  // tasks 0 and 2 hold iterations 1, 4 and 3
}

TEST(FrameSplit, TaskArgumentsAreChecked) {
  TestDir dir;
  const std::string scene = split_scene();
  ProcessResult r = run_nimbus({"render", scene, "--task", "4", "--tasks", "4"}, dir);
  EXPECT_TRUE(exited_with(r, 2)) << r.describe();
  EXPECT_NE(r.err.find("--task 4 is not one of the tasks 0 to 3"), std::string::npos) << r.err;
  r = run_nimbus({"render", scene, "--task", "1"}, dir);
  EXPECT_TRUE(exited_with(r, 2)) << r.describe();
  EXPECT_NE(r.err.find("--task and --tasks go together"), std::string::npos) << r.err;
  r = run_nimbus({"render", scene, "-q", "--iterations", "2", "--task", "2", "--tasks", "3"}, dir);
  EXPECT_TRUE(exited_with(r, 1)) << r.describe();
  EXPECT_NE(r.err.find("leave this task none"), std::string::npos) << r.err;
}

// Each task stops on its own budget; a task's checkpoint resumes that task only, and its error estimate
// pairs its own odd and even iterations.
TEST(FrameSplit, TasksStopOnTheirOwnAndResumeOnlyThemselves) {
  TestDir dir;
  const std::string scene = split_scene();
  const std::string part = dir.file("p.exr");
  ASSERT_TRUE(
      render(dir, scene, part, {"--caustics", "off", "--iterations", "8", "--task", "1", "--tasks", "2"}));
  ProcessResult r = run_nimbus({"render", scene, "-q", "-o", part, "--caustics", "off", "--iterations", "12",
                                "--task", "0", "--tasks", "2", "--resume"},
                               dir);
  EXPECT_TRUE(exited_with(r, 1)) << r.describe();
  EXPECT_NE(r.err.find("task"), std::string::npos) << r.err;
  ASSERT_TRUE(render(dir, scene, part,
                     {"--caustics", "off", "--iterations", "12", "--task", "1", "--tasks", "2", "--resume"}));
  auto img = read_exr(part);
  ASSERT_TRUE(img);
  EXPECT_EQ(meta_number(*img, "nimbus:iterations"), 6.0);

  ASSERT_TRUE(render(dir, scene, dir.file("t.exr"),
                     {"--caustics", "off", "--target-error", "0.05", "--task", "1", "--tasks", "2"}));
  img = read_exr(dir.file("t.exr"));
  ASSERT_TRUE(img);
  EXPECT_EQ(meta_string(*img, "nimbus:stopped_by"), "target_error");
  EXPECT_LT(meta_number(*img, "nimbus:estimated_relmse").value_or(1), 0.05);
}

}  // namespace frame_split_test
}  // namespace nimbus::e2e
