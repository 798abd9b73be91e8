// Resuming through the real CLI: a render stopped at any point (finished, Ctrl-C, killed outright) and
// resumed to N iterations is bit-identical to an uninterrupted render of N, because random numbers are
// keyed by iteration and the checkpoint restores the exact double sums. And a checkpoint that does not
// belong to the render is refused.
#include <gtest/gtest.h>
#include <signal.h>

#include <bit>
#include <filesystem>
#include <fstream>
#include <thread>

#include "e2e_support.hpp"
#include "film/checkpoint.hpp"

namespace nimbus::e2e {
namespace resume_cli_test {

bool contains(const std::string &text, const std::string &part) {
  return text.find(part) != std::string::npos;
}

// `nimbus render box.yaml -o OUT` with a fixed seed and thread count, plus `extra`.
ProcessResult render_box(const TestDir &dir, const std::string &out, const std::vector<std::string> &extra) {
  std::vector<std::string> args = {"render", scene("box.yaml"), "-o", out, "--seed", "11", "--threads", "2"};
  args.insert(args.end(), extra.begin(), extra.end());
  return run_nimbus(args, dir);
}

// Every channel of every layer, as bit patterns, with the iteration count; empty after a recorded failure.
struct Pixels {
  std::map<std::string, std::vector<uint32_t>> channels;
  double iterations = -1;
};

Pixels pixels_of(const std::string &exr) {
  Pixels p;
  const auto img = read_exr(exr);
  if (!img) return p;
  for (const auto &[name, plane] : img->channels) {
    auto &bits = p.channels[name];
    for (float v : plane) bits.push_back(std::bit_cast<uint32_t>(v));
  }
  p.iterations = meta_number(*img, "nimbus:iterations").value_or(-1);
  return p;
}

void expect_identical(const std::string &a, const std::string &b) {
  const Pixels pa = pixels_of(a), pb = pixels_of(b);
  ASSERT_FALSE(pa.channels.empty());
  EXPECT_EQ(pa.iterations, pb.iterations);
  ASSERT_EQ(pa.channels.size(), pb.channels.size());
  for (const auto &[name, bits] : pa.channels) {
    ASSERT_TRUE(pb.channels.count(name)) << name;
    size_t differing = 0;
    for (size_t i = 0; i < bits.size(); ++i) differing += bits[i] != pb.channels.at(name)[i];
    EXPECT_EQ(differing, 0u) << "channel " << name << " of " << b << " differs from " << a;
  }
}

TEST(Resume, ThreeThenResumedToSixEqualsSixUninterrupted) {
  TestDir dir;
  const std::string full = dir.file("full.exr"), part = dir.file("part.exr");
  const std::vector<std::string> elements = {"--elements", "albedo,depth"};
  auto with = [&](std::vector<std::string> args) {
    args.insert(args.end(), elements.begin(), elements.end());
    return args;
  };
  ProcessResult r = render_box(dir, full, with({"--iterations", "6", "-q"}));
  ASSERT_TRUE(exited_with(r, 0)) << r.describe();
  r = render_box(dir, part, with({"--iterations", "3", "-q"}));
  ASSERT_TRUE(exited_with(r, 0)) << r.describe();
  // The finished render keeps its checkpoint so that it can be extended.
  ASSERT_TRUE(std::filesystem::exists(part + ".ckpt"));
  EXPECT_EQ(peek_checkpoint(part + ".ckpt")->iterations, 3u);

  r = render_box(dir, part, with({"--iterations", "6", "--resume"}));
  ASSERT_TRUE(exited_with(r, 0)) << r.describe();
  EXPECT_TRUE(contains(r.err, "resumed from iteration 3")) << r.err;
  expect_identical(full, part);
  const auto img = read_exr(part);
  ASSERT_TRUE(img);
  EXPECT_EQ(meta_number(*img, "nimbus:resumed_from"), std::optional<double>(3));
  EXPECT_EQ(peek_checkpoint(part + ".ckpt")->iterations, 6u);
  EXPECT_EQ(dir.temporaries(), std::vector<std::string>{});
}

TEST(Resume, SplattingIntegratorResumesExactly) {
  // The light tracer splats into per-worker buffers merged after each iteration: the checkpoint must hold
  // them merged, and the resumed sums must continue in the same order.
  TestDir dir;
  const std::string full = dir.file("full.exr"), part = dir.file("part.exr"), ckpt = dir.file("lt.ckpt");
  const std::vector<std::string> lt = {"--integrator", "nimbus.lt", "-q", "--checkpoint", ckpt};
  auto with = [&](std::vector<std::string> args) {
    args.insert(args.end(), lt.begin(), lt.end());
    return args;
  };
  ProcessResult r = render_box(dir, full, with({"--iterations", "4"}));
  ASSERT_TRUE(exited_with(r, 0)) << r.describe();
  r = render_box(dir, part, with({"--iterations", "2"}));
  ASSERT_TRUE(exited_with(r, 0)) << r.describe();
  r = render_box(dir, part, with({"--iterations", "4", "--resume"}));
  ASSERT_TRUE(exited_with(r, 0)) << r.describe();
  expect_identical(full, part);
}

// The caustics solver learns as it renders (photon budget, pass schedule, per-pixel variances, light
// selection, the emission map), so a resumed render equals an uninterrupted one only with that state
// restored and the current photon map traced again. The box at 192x144 makes a photon pass every few
// iterations; 9 falls inside a map's service, and the resumed part runs on one thread.
void expect_caustics_solver_resumes_exactly(const std::vector<std::string> &options) {
  TestDir dir;
  std::string text = read_bytes(scene("box.yaml"));
  const auto replace = [&](const std::string &from, const std::string &to) {
    const size_t at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
  };
  replace("resolution: [64, 48]", "resolution: [192, 144]");
  replace("integrator: nimbus.pt", "integrator: nimbus.caustics");
  const std::string box = dir.file("caustic-box.yaml");
  write_bytes(box, text);
  const std::string full = dir.file("full.exr"), part = dir.file("part.exr");
  auto render = [&](const std::string &out, const std::string &iterations, const std::string &threads,
                    std::vector<std::string> extra) {
    std::vector<std::string> args = {
        "render",       box,        "-o",         out,        "--seed", "11", "--threads", threads,
        "--iterations", iterations, "--elements", "caustics", "-q"};
    args.insert(args.end(), extra.begin(), extra.end());
    args.insert(args.end(), options.begin(), options.end());
    return run_nimbus(args, dir);
  };
  ProcessResult r = render(full, "24", "2", {});
  ASSERT_TRUE(exited_with(r, 0)) << r.describe();
  r = render(part, "9", "2", {});
  ASSERT_TRUE(exited_with(r, 0)) << r.describe();
  r = render(part, "24", "1", {"--resume"});
  ASSERT_TRUE(exited_with(r, 0)) << r.describe();
  EXPECT_FALSE(contains(r.err, "warning")) << r.err;
  expect_identical(full, part);
  // More than one photon pass, and the same ones.
  const auto a = read_exr(full), b = read_exr(part);
  ASSERT_TRUE(a && b);
  const auto passes = meta_number(*a, "nimbus:stat:caustics_photon_passes");
  ASSERT_TRUE(passes);
  EXPECT_GE(*passes, 3.0);
  EXPECT_EQ(meta_number(*b, "nimbus:stat:caustics_photon_passes"), passes);
  EXPECT_EQ(meta_number(*b, "nimbus:stat:caustics_photon_paths"),
            meta_number(*a, "nimbus:stat:caustics_photon_paths"));
  const auto slots = meta_number(*a, "nimbus:stat:caustics_emission_map_slots");
  ASSERT_TRUE(slots);
  EXPECT_EQ(meta_number(*b, "nimbus:stat:caustics_emission_map_slots"), slots);
  if (options.size() > 1 && options[1] == "adaptive-map") {
    EXPECT_GE(*slots, 1.0) << "the map learnt";
  }
}

TEST(Resume, CausticsSolverResumesExactlyWithItsLearntState) { expect_caustics_solver_resumes_exactly({}); }

TEST(Resume, CausticsSolverResumesExactlyWithItsEmissionMap) {
  expect_caustics_solver_resumes_exactly({"--photon_emission", "adaptive-map"});
}

// Starts a render that would take minutes; returns once it has reported an iteration (and, if `file` is
// given, once that file exists).
std::unique_ptr<Process> start_long_render(const TestDir &dir, const std::vector<std::string> &args,
                                           const std::string &file = "") {
  std::vector<std::string> all = {"render", scene("box.yaml"), "--seed", "11", "--threads",
                                  "2",      "--iterations",    "100000"};
  all.insert(all.end(), args.begin(), args.end());
  auto p = std::make_unique<Process>(nimbus_argv(all), dir.path());
  EXPECT_TRUE(p->wait_for_stderr([](const std::string &e) { return contains(e, "iteration "); },
                                 std::chrono::seconds(60)))
      << "no progress reported";
  for (int k = 0; !file.empty() && !std::filesystem::exists(file) && k < 600; ++k) {
    p->wait_for_stderr([](const std::string &) { return false; }, std::chrono::milliseconds(100));
  }
  return p;
}

// Resumes `exr` to one more iteration than its checkpoint holds, renders the same total afresh, and
// expects the two to be identical.
void expect_resumes_exactly(const TestDir &dir, const std::string &exr, const std::string &ckpt) {
  const auto held = peek_checkpoint(ckpt);
  ASSERT_TRUE(held.ok()) << held.error().message;
  ASSERT_GE(held->iterations, 1u);
  const std::string total = std::to_string(held->iterations + 1);
  ProcessResult r = render_box(dir, exr, {"--iterations", total, "--resume", "--checkpoint", ckpt, "-q"});
  ASSERT_TRUE(exited_with(r, 0)) << r.describe();
  const std::string fresh = dir.file("fresh.exr");
  r = render_box(dir, fresh, {"--iterations", total, "-q"});
  ASSERT_TRUE(exited_with(r, 0)) << r.describe();
  expect_identical(fresh, exr);
}

TEST(Resume, CtrlCLeavesACheckpointThatResumesExactly) {
  TestDir dir;
  const std::string exr = dir.file("long.exr"), ckpt = dir.file("long.ckpt");
  // No periodic checkpoints: the one found afterwards was written by the Ctrl-C stop.
  auto p = start_long_render(dir, {"-o", exr, "--checkpoint", ckpt, "--checkpoint-every", "0"});
  EXPECT_FALSE(std::filesystem::exists(ckpt));
  p->send_signal(SIGINT);
  const ProcessResult r = p->wait(std::chrono::seconds(120));
  ASSERT_TRUE(exited_with(r, 130)) << r.describe();
  EXPECT_TRUE(contains(r.err, "checkpoint " + ckpt)) << r.err;
  const auto img = read_exr(exr);
  ASSERT_TRUE(img);
  // The checkpoint holds exactly what the image does.
  EXPECT_EQ(meta_number(*img, "nimbus:iterations"), std::optional<double>(peek_checkpoint(ckpt)->iterations));
  expect_resumes_exactly(dir, exr, ckpt);
}

TEST(Resume, PeriodicCheckpointSurvivesAHardKill) {
  TestDir dir;
  const std::string exr = dir.file("killed.exr"), ckpt = exr + ".ckpt";
  auto p = start_long_render(dir, {"-o", exr, "--checkpoint-every", "0.001"}, ckpt);
  ASSERT_TRUE(std::filesystem::exists(ckpt)) << "no periodic checkpoint";
  p->send_signal(SIGKILL);
  const ProcessResult r = p->wait(std::chrono::seconds(60));
  ASSERT_EQ(r.signal, SIGKILL) << r.describe();
  // No final image was written, but the work is not lost.
  EXPECT_FALSE(std::filesystem::exists(exr));
  expect_resumes_exactly(dir, exr, ckpt);
}

TEST(Resume, ResumingAFinishedRenderToItsOwnCountRewritesTheSameImage) {
  TestDir dir;
  const std::string a = dir.file("a.exr"), b = dir.file("b.exr");
  ProcessResult r = render_box(dir, a, {"--iterations", "2", "-q"});
  ASSERT_TRUE(exited_with(r, 0)) << r.describe();
  r = render_box(dir, b, {"--iterations", "2", "--resume", "--checkpoint", a + ".ckpt", "-q"});
  ASSERT_TRUE(exited_with(r, 0)) << r.describe();
  expect_identical(a, b);
}

TEST(Resume, WithoutACheckpointIsAnErrorNamingIt) {
  TestDir dir;
  const std::string out = dir.file("x.exr");
  const ProcessResult r = render_box(dir, out, {"--iterations", "2", "--resume"});
  EXPECT_TRUE(exited_with(r, 1)) << r.describe();
  EXPECT_TRUE(contains(r.err, "cannot resume")) << r.err;
  EXPECT_TRUE(contains(r.err, out + ".ckpt")) << r.err;
  EXPECT_EQ(dir.entries(), std::vector<std::string>{});
}

TEST(Resume, CheckpointOfAnotherRenderIsRefused) {
  TestDir dir;
  const std::string out = dir.file("x.exr");
  // The scene is copied so that it can be edited.
  const std::string yaml = dir.file("box.yaml");
  std::filesystem::copy_file(scene("box.yaml"), yaml);
  auto render = [&](std::vector<std::string> extra) {
    std::vector<std::string> args = {"render", yaml, "-o", out, "--threads", "2", "-q", "--iterations", "3"};
    args.insert(args.end(), extra.begin(), extra.end());
    return run_nimbus(args, dir);
  };
  ProcessResult r = render({"--iterations", "1"});
  ASSERT_TRUE(exited_with(r, 0)) << r.describe();
  const std::string before = read_bytes(out + ".ckpt");

  r = render({"--resume", "--seed", "99"});
  EXPECT_TRUE(exited_with(r, 1)) << r.describe();
  EXPECT_TRUE(contains(r.err, "seed")) << r.err;
  r = render({"--resume", "--elements", "albedo"});
  EXPECT_TRUE(exited_with(r, 1)) << r.describe();
  EXPECT_TRUE(contains(r.err, "elements: checkpoint '', this render 'albedo'")) << r.err;
  r = render({"--resume", "--integrator", "nimbus.lt"});
  EXPECT_TRUE(exited_with(r, 1)) << r.describe();
  EXPECT_TRUE(contains(r.err, "integrator 'nimbus.pt'; this render uses 'nimbus.lt'")) << r.err;
  std::ofstream(yaml, std::ios::app) << "# edited\n";
  r = render({"--resume"});
  EXPECT_TRUE(exited_with(r, 1)) << r.describe();
  EXPECT_TRUE(contains(r.err, "scene_hash")) << r.err;
  // A refused resume leaves the checkpoint alone.
  EXPECT_EQ(read_bytes(out + ".ckpt"), before);
}

TEST(Resume, AFreshRenderWarnsBeforeReplacingACheckpoint) {
  TestDir dir;
  const std::string out = dir.file("x.exr");
  ProcessResult r = render_box(dir, out, {"--iterations", "2", "-q"});
  ASSERT_TRUE(exited_with(r, 0)) << r.describe();
  r = render_box(dir, out, {"--iterations", "1", "-q"});
  ASSERT_TRUE(exited_with(r, 0)) << r.describe();
  EXPECT_TRUE(contains(r.err, "warning: checkpoint '" + out + ".ckpt' (2 iterations) will be replaced"))
      << r.err;
  EXPECT_EQ(peek_checkpoint(out + ".ckpt")->iterations, 1u);
}

TEST(Resume, BadCheckpointOptionsAreUsageErrors) {
  TestDir dir;
  for (const auto &args :
       std::vector<std::vector<std::string>>{{"--checkpoint-every", "-1"}, {"--checkpoint"}}) {
    std::vector<std::string> all = {"render", scene("box.yaml"), "-o", dir.file("x.exr")};
    all.insert(all.end(), args.begin(), args.end());
    const ProcessResult r = run_nimbus(all, dir);
    EXPECT_TRUE(exited_with(r, 2)) << args[0] << ": " << r.describe();
    EXPECT_TRUE(contains(r.err, "--checkpoint")) << r.err;
  }
}

}  // namespace resume_cli_test
}  // namespace nimbus::e2e
