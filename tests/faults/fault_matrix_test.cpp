// The fault matrix: org.nimbus.test.faults (fault_plugin.cpp) fails each integrator hook in each way, and
// the CLI must answer every case the same way: one error line naming the plugin and the hook, a non-zero
// exit code, and either a complete image of the iterations finished before the fault (EXR with its sample
// count, PNG, no temporary left) or, when no iteration finished, the previous output file untouched. The
// plugin's pixels are known exactly, so an image that kept part of a failed iteration shows in them.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "e2e_support.hpp"

namespace nimbus::e2e {
namespace fault_matrix_test {

constexpr uint32_t kWidth = 72, kHeight = 40;  // 3 x 2 tiles of 32 pixels, the last ones partial
constexpr uint64_t kIterations = 5, kFaultIteration = 3;

struct Case {
  std::string hook, fault;
  int status = -6;
};

void PrintTo(const Case &c, std::ostream *os) { *os << c.hook << " " << c.fault << " " << c.status; }

std::string case_name(const ::testing::TestParamInfo<Case> &info) {
  std::string s = info.param.hook + "_" + info.param.fault;
  if (info.param.fault == "status")
    s += (info.param.status < 0 ? "_minus" : "_") + std::to_string(std::abs(info.param.status));
  return s;
}

std::string write_scene(const TestDir &dir) {
  const std::string path = dir.file("faults.yaml");
  write_bytes(path, "render:\n  resolution: [" + std::to_string(kWidth) + ", " + std::to_string(kHeight) +
                        "]\n  integrator: org.nimbus.test.faults\n"
                        "camera: { position: [0, -4, 1], look_at: [0, 0, 1], up: [0, 0, 1], fov: 40 }\n");
  return path;
}

struct FaultRun {
  ProcessResult result;
  std::string exr, previous_exr_bytes;
};

// Renders the scene with the fault; a file already at the output path holds "previous".
FaultRun render_with_fault(const TestDir &dir, const Case &c, const std::vector<std::string> &extra = {}) {
  FaultRun run;
  run.exr = dir.file("out.exr");
  run.previous_exr_bytes = "previous";
  write_bytes(run.exr, run.previous_exr_bytes);
  std::vector<std::string> argv = {"/usr/bin/env",
                                   std::string("NIMBUS_PLUGIN_PATH=") + NIMBUS_FAULT_PLUGIN_DIR,
                                   NIMBUS_CLI,
                                   "render",
                                   write_scene(dir),
                                   "-o",
                                   run.exr,
                                   "--elements",
                                   "fault_splat",
                                   "--threads",
                                   "2",
                                   "-q",
                                   "--fault",
                                   c.fault,
                                   "--fault_hook",
                                   c.hook,
                                   "--fault_iteration",
                                   std::to_string(kFaultIteration),
                                   "--fault_status",
                                   std::to_string(c.status)};
  argv.insert(argv.end(), extra.begin(), extra.end());
  if (extra.empty()) argv.insert(argv.end(), {"--iterations", std::to_string(kIterations)});
  run.result = Process(argv, dir.path()).wait(std::chrono::seconds(120));
  return run;
}

// The iterations the image must hold: those finished before the fault; an end_iteration's samples are in.
uint64_t complete_iterations(const Case &c) {
  if (c.hook == "prepare" || c.hook == "begin_render") return 0;
  return c.hook == "end_iteration" ? kFaultIteration : kFaultIteration - 1;
}

// Every pixel is exactly what `iterations` complete iterations give (each sample is the same value, so
// the mean is exact), except `lost`: pixels whose sample of the fault iteration the film refused.
void expect_exact_image(const ImageLayers &img, uint64_t iterations, const std::vector<uint32_t> &lost = {}) {
  ASSERT_EQ(img.width, kWidth);
  ASSERT_EQ(img.height, kHeight);
  EXPECT_EQ(meta_number(img, "nimbus:iterations").value_or(-1), double(iterations));
  const std::vector<float> &r = plane(img, "R"), &g = plane(img, "G"), &splat = plane(img, "fault_splat.R");
  ASSERT_EQ(r.size(), size_t(kWidth) * kHeight);
  ASSERT_EQ(splat.size(), r.size());
  size_t wrong = 0;
  for (uint32_t y = 0; y < kHeight; ++y)
    for (uint32_t x = 0; x < kWidth; ++x) {
      const size_t i = size_t(y) * kWidth + x;
      const bool is_lost = std::find(lost.begin(), lost.end(), uint32_t(i)) != lost.end();
      const double keep = is_lost ? double(iterations - 1) / double(iterations) : 1.0;
      const float want_r = float((x + 0.5) / kWidth * keep), want_g = float((y + 0.5) / kHeight * keep);
      if (std::abs(r[i] - want_r) > 1e-6f * want_r || std::abs(g[i] - want_g) > 1e-6f * want_g ||
          splat[i] != 1.0f)
        ++wrong;
    }
  EXPECT_EQ(wrong, 0u) << "pixels that hold part of an iteration or lost samples";
}

void expect_one_error_line(const ProcessResult &r, const std::vector<std::string> &words) {
  EXPECT_TRUE(r.exited && r.exit_code == 1) << r.describe();
  size_t lines = 0;
  std::string line_with_all;
  for (size_t at = 0; (at = r.err.find("nimbus: error: ", at)) != std::string::npos; ++at) {
    const std::string line = r.err.substr(at, r.err.find('\n', at) - at);
    bool all = true;
    for (const std::string &w : words) all = all && line.find(w) != std::string::npos;
    if (all) line_with_all = line, ++lines;
  }
  EXPECT_EQ(lines, 1u) << "one error line naming " << ::testing::PrintToString(words) << ":\n" << r.err;
}

class Faults : public ::testing::TestWithParam<Case> {};

TEST_P(Faults, NamedOnOneLineWithTheCompleteIterationsWritten) {
  const Case &c = GetParam();
  TestDir dir;
  const std::vector<std::string> sleep_budget = {"--time", "1"};
  const FaultRun run =
      render_with_fault(dir, c, c.fault == "sleep" ? sleep_budget : std::vector<std::string>{});
  std::vector<std::string> words = {"org.nimbus.test.faults", c.hook};
  if (c.fault == "status") {
    const char *const texts[] = {
        "",          "invalid argument", "unsupported", "out of memory", "version mismatch",
        "cancelled", "internal error"};
    words.push_back(c.status < 0 && c.status >= -6 ? texts[-c.status] : "status " + std::to_string(c.status));
  }
  if (c.fault == "throw") words.push_back("internal error");
  if (c.fault == "missing_service") words.push_back("nimbus.host.film@99");
  if (c.fault == "sleep") words.push_back("past the time budget");
  expect_one_error_line(run.result, words);
  if (c.fault == "throw")
    EXPECT_NE(run.result.err.find("injected fault in " + c.hook), std::string::npos) << run.result.err;
  EXPECT_TRUE(dir.temporaries().empty()) << ::testing::PrintToString(dir.temporaries());

  const uint64_t iterations = complete_iterations(c);
  if (iterations == 0) {
    EXPECT_EQ(read_bytes(run.exr), run.previous_exr_bytes) << "the previous output must stay untouched";
    return;
  }
  const auto img = read_exr(run.exr);
  ASSERT_TRUE(img);
  expect_exact_image(*img, iterations);
  EXPECT_EQ(meta_string(*img, "nimbus:stopped_by").value_or(""), "error");
  EXPECT_TRUE(std::filesystem::exists(dir.file("out.png")));
}

std::vector<Case> matrix() {
  std::vector<Case> cases;
  for (const char *hook : {"prepare", "begin_render", "begin_iteration", "render_tile", "end_iteration"}) {
    for (int status : {-1, -2, -3, -4, -5, -6, 7}) cases.push_back({hook, "status", status});
    for (const char *fault : {"throw", "missing_service", "sleep"}) cases.push_back({hook, fault});
  }
  return cases;
}

INSTANTIATE_TEST_SUITE_P(EveryHook, Faults, ::testing::ValuesIn(matrix()), case_name);

// Values the film refuses: NaN and infinity (dropped: one per tile's first pixel at the fault iteration)
// and writes outside the worker's tile (dropped: another thread owns those pixels). The render finishes,
// the image is written, and the error names the plugin, the hook and the count.
TEST(FaultValues, NanInfinityAndWritesOutsideTheTileAreDroppedAndReported) {
  const std::vector<uint32_t> tile_corners = {0, 32, 64, 32 * kWidth, 32 * kWidth + 32, 32 * kWidth + 64};
  for (const char *fault : {"nan", "inf", "outside_tile"}) {
    SCOPED_TRACE(fault);
    TestDir dir;
    const FaultRun run = render_with_fault(dir, {"render_tile", fault});
    const bool outside = std::string(fault) == "outside_tile";
    expect_one_error_line(run.result, {"org.nimbus.test.faults", "render_tile",
                                       outside ? "4 samples outside its tile" : "6 NaN or infinite samples"});
    const auto img = read_exr(run.exr);
    ASSERT_TRUE(img);
    expect_exact_image(*img, kIterations, outside ? std::vector<uint32_t>{} : tile_corners);
    EXPECT_EQ(meta_number(*img, "nimbus:nonfinite_samples").value_or(-1), outside ? 0.0 : 6.0);
  }
}

// Without a fault the plugin's image is the exact one: the checks above can tell.
TEST(FaultValues, NoFaultRendersTheExactImage) {
  TestDir dir;
  const FaultRun run = render_with_fault(dir, {"render_tile", "none"});
  ASSERT_TRUE(exited_with(run.result, 0)) << run.result.describe();
  const auto img = read_exr(run.exr);
  ASSERT_TRUE(img);
  expect_exact_image(*img, kIterations);
}

}  // namespace fault_matrix_test
}  // namespace nimbus::e2e
