// Ctrl-C: the first SIGINT (or SIGTERM) finishes the current iteration and writes complete files (exit
// 130, or 143); the output file is replaced by rename, so an earlier image at the same path is never left
// truncated.
#include <gtest/gtest.h>
#include <signal.h>

#include <cmath>
#include <memory>
#include <regex>
#include <utility>
#include <vector>

#include "e2e_support.hpp"

namespace nimbus::e2e {
namespace interrupt_test {

constexpr int kManyIterations = 100000;  // far more than any run of this test reaches
const std::string kOldContent = "an earlier render, not an EXR\n";

bool shows_progress(const std::string &err) { return err.find("iteration ") != std::string::npos; }

// Starts a render that would take minutes and waits until it reports an iteration, so the SIGINT handler
// is installed and the film holds at least one iteration.
// scene_path: the scene to render; extra: more arguments (e.g. the integrator).
std::unique_ptr<Process> start_long_render(const TestDir &dir, const std::string &exr,
                                           const std::string &scene_path = scene("box.yaml"),
                                           const std::vector<std::string> &extra = {}) {
  std::vector<std::string> args = {"render", scene_path,     "-o",
                                   exr,      "--iterations", std::to_string(kManyIterations)};
  args.insert(args.end(), extra.begin(), extra.end());
  auto p = std::make_unique<Process>(nimbus_argv(args), dir.path());
  // Generous: under the sanitizers start-up alone takes seconds.
  EXPECT_TRUE(p->wait_for_stderr(shows_progress, std::chrono::seconds(60))) << "no progress reported";
  return p;
}

// What the CLI's closing line says it wrote: "nimbus: N iterations in S s -> ... (interrupted)".
std::optional<uint64_t> reported_iterations(const std::string &err) {
  std::smatch m;
  if (!std::regex_search(err, m, std::regex(R"(nimbus: (\d+) iterations in .*\(interrupted\))")))
    return std::nullopt;
  return std::stoull(m[1]);
}

TEST(Interrupt, CtrlCFinishesTheIterationAndWritesCompleteFiles) {
  TestDir dir;
  const std::string exr = dir.file("long.exr");
  auto p = start_long_render(dir, exr);
  p->send_signal(SIGINT);
  const ProcessResult r = p->wait(std::chrono::seconds(120));
  ASSERT_TRUE(exited_with(r, 130)) << r.describe();

  const auto img = read_exr(exr);
  ASSERT_TRUE(img);
  const std::optional<double> n = meta_number(*img, "nimbus:iterations");
  ASSERT_TRUE(n) << "nimbus:iterations missing";
  EXPECT_GE(*n, 1);
  EXPECT_LT(*n, kManyIterations);
  EXPECT_EQ(meta_string(*img, "nimbus:stopped_by"), std::optional<std::string>("cancel"));
  // The header and the CLI's summary agree on how many iterations the image holds.
  EXPECT_EQ(reported_iterations(r.err), std::optional<uint64_t>(uint64_t(*n))) << r.err;
  for (const char *c : {"R", "G", "B"}) {
    const std::vector<float> &px = plane(*img, c);
    EXPECT_EQ(px.size(), 64u * 48u) << c;
    for (float v : px) ASSERT_TRUE(std::isfinite(v)) << c;
  }
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"long.exr", "long.exr.ckpt", "long.png"}));
}

// SIGTERM (a scheduler's or `kill`'s) stops a render as Ctrl-C does: complete files, exit 128 + 15.
TEST(Interrupt, SigtermFinishesTheIterationAndWritesCompleteFiles) {
  TestDir dir;
  const std::string exr = dir.file("long.exr");
  auto p = start_long_render(dir, exr);
  p->send_signal(SIGTERM);
  const ProcessResult r = p->wait(std::chrono::seconds(120));
  ASSERT_TRUE(exited_with(r, 143)) << r.describe();
  const auto img = read_exr(exr);
  ASSERT_TRUE(img);
  EXPECT_EQ(meta_string(*img, "nimbus:stopped_by"), std::optional<std::string>("cancel"));
  EXPECT_GE(meta_number(*img, "nimbus:iterations").value_or(0), 1);
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"long.exr", "long.exr.ckpt", "long.png"}));
}

// The same with the light tracer (splats from every thread) and with the caustics solver between photon
// passes (a scene whose point light shines through glass): a complete, finite image and exit 130.
TEST(Interrupt, CtrlCStopsTheLightTracerAndTheCausticsSolverCleanly) {
  const std::string sphere_point = std::string(NIMBUS_SOURCE_DIR) + "/scenes/caustics/sphere-point.yaml";
  for (const auto &[path, integrator] :
       {std::pair{scene("box.yaml"), std::string("lt")}, std::pair{sphere_point, std::string("caustics")}}) {
    TestDir dir;
    const std::string exr = dir.file("long.exr");
    auto p = start_long_render(dir, exr, path, {"--integrator", integrator});
    p->send_signal(SIGINT);
    const ProcessResult r = p->wait(std::chrono::seconds(120));
    ASSERT_TRUE(exited_with(r, 130)) << integrator << ": " << r.describe();
    const auto img = read_exr(exr);
    ASSERT_TRUE(img) << integrator;
    EXPECT_EQ(meta_string(*img, "nimbus:stopped_by"), std::optional<std::string>("cancel")) << integrator;
    EXPECT_EQ(meta_string(*img, "nimbus:integrator"), std::optional<std::string>("nimbus." + integrator));
    EXPECT_GE(meta_number(*img, "nimbus:iterations").value_or(0), 1) << integrator;
    for (const char *c : {"R", "G", "B"})
      for (float v : plane(*img, c)) ASSERT_TRUE(std::isfinite(v)) << integrator << " " << c;
    EXPECT_EQ(dir.temporaries(), std::vector<std::string>{}) << integrator;
  }
}

TEST(Interrupt, EarlierOutputIsReplacedWholeNeverTruncated) {
  TestDir dir;
  const std::string exr = dir.file("out.exr");
  write_bytes(exr, kOldContent);
  auto p = start_long_render(dir, exr);
  // While the render runs, the earlier file is untouched: nothing opens the target for writing up front.
  EXPECT_EQ(read_bytes(exr), kOldContent);
  p->send_signal(SIGINT);
  const ProcessResult r = p->wait(std::chrono::seconds(120));
  ASSERT_TRUE(exited_with(r, 130)) << r.describe();
  // A graceful stop writes a complete new image (read_exr fails the test on a truncated or old file).
  const auto img = read_exr(exr);
  ASSERT_TRUE(img);
  EXPECT_EQ(meta_string(*img, "nimbus:stopped_by"), std::optional<std::string>("cancel"));
  EXPECT_EQ(dir.temporaries(), std::vector<std::string>{});
}

TEST(Interrupt, SecondCtrlCStopsAtOnceAndLeavesOldOrCompleteFile) {
  TestDir dir;
  const std::string exr = dir.file("out.exr");
  write_bytes(exr, kOldContent);
  auto p = start_long_render(dir, exr);
  p->send_signal(SIGINT);
  p->send_signal(SIGINT);
  const ProcessResult r = p->wait(std::chrono::seconds(120));
  // Killed by the re-raised SIGINT, or the first one's graceful stop won the race.
  EXPECT_TRUE((!r.exited && r.signal == SIGINT) || exited_with(r, 130)) << r.describe();
  // Wherever the second signal landed, even mid-write, `out.exr` is the old file or a complete new one.
  if (read_bytes(exr) != kOldContent) {
    const auto img = read_exr(exr);
    ASSERT_TRUE(img) << "out.exr is neither the earlier file nor a readable EXR";
    EXPECT_EQ(plane(*img, "R").size(), 64u * 48u);
  }
}

}  // namespace interrupt_test
}  // namespace nimbus::e2e
