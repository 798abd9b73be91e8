// The CLI's contract for bad input and informational commands: exit codes (1 failure, 2 usage), messages
// that name what is wrong, and no output files from a render that never started.
#include <gtest/gtest.h>

#include <algorithm>
#include <regex>
#include <sstream>

#include "e2e_support.hpp"

namespace nimbus::e2e {
namespace cli_test {

bool contains(const std::string &text, const std::string &part) {
  return text.find(part) != std::string::npos;
}

// A failed render must not leave an image (or a temporary) behind.
void expect_no_output(const TestDir &dir) { EXPECT_EQ(dir.entries(), std::vector<std::string>{}); }

TEST(Cli, SyntaxErrorNamesFileLineColumn) {
  TestDir dir;
  const std::string path = scene("syntax_error.yaml");
  const ProcessResult r = run_nimbus({"render", path, "-o", dir.file("x.exr")}, dir);
  EXPECT_TRUE(exited_with(r, 1)) << r.describe();
  const size_t at = r.err.find(path + ":");
  ASSERT_NE(at, std::string::npos) << r.err;
  const std::string position = r.err.substr(at + path.size());
  std::smatch m;
  ASSERT_TRUE(std::regex_search(position, m, std::regex(R"(^:(\d+):(\d+): error)"))) << r.err;
  // The unclosed '[' opens on line 5; the parser may only notice on the next line.
  const int line = std::stoi(m[1]), column = std::stoi(m[2]);
  EXPECT_TRUE(line == 5 || line == 6) << r.err;
  EXPECT_GE(column, 1);
  expect_no_output(dir);
}

TEST(Cli, MissingSceneFileNamesThePath) {
  TestDir dir;
  const std::string path = dir.file("no-such-scene.yaml");
  const ProcessResult r = run_nimbus({"render", path, "-o", dir.file("x.exr")}, dir);
  EXPECT_TRUE(exited_with(r, 1)) << r.describe();
  EXPECT_TRUE(contains(r.err, path)) << r.err;
  expect_no_output(dir);
}

TEST(Cli, UnknownOptionIsUsageError) {
  TestDir dir;
  const ProcessResult r =
      run_nimbus({"render", scene("box.yaml"), "--frobnicate", "-o", dir.file("x.exr")}, dir);
  EXPECT_TRUE(exited_with(r, 2)) << r.describe();
  EXPECT_TRUE(contains(r.err, "--frobnicate")) << r.err;
  expect_no_output(dir);
}

TEST(Cli, ZeroIterationsIsUsageError) {
  TestDir dir;
  const ProcessResult r =
      run_nimbus({"render", scene("box.yaml"), "--iterations", "0", "-o", dir.file("x.exr")}, dir);
  EXPECT_TRUE(exited_with(r, 2)) << r.describe();
  EXPECT_TRUE(contains(r.err, "--iterations")) << r.err;
  expect_no_output(dir);
}

TEST(Cli, UnknownIntegratorNamesTheId) {
  TestDir dir;
  const ProcessResult r =
      run_nimbus({"render", scene("unknown_integrator.yaml"), "-o", dir.file("x.exr")}, dir);
  EXPECT_TRUE(r.exited && !r.timed_out && r.exit_code != 0) << r.describe();
  EXPECT_TRUE(contains(r.err, "nimbus.nonexistent")) << r.err;
  expect_no_output(dir);
}

TEST(Cli, UnknownRenderElementNamesIt) {
  TestDir dir;
  const ProcessResult r =
      run_nimbus({"render", scene("box.yaml"), "--elements", "nosuch", "-o", dir.file("x.exr")}, dir);
  EXPECT_TRUE(r.exited && !r.timed_out && r.exit_code != 0) << r.describe();
  EXPECT_TRUE(contains(r.err, "nosuch")) << r.err;
  expect_no_output(dir);
}

TEST(Cli, VersionPrintsTheVersion) {
  TestDir dir;
  const ProcessResult r = run_nimbus({"--version"}, dir);
  EXPECT_TRUE(exited_with(r, 0)) << r.describe();
  EXPECT_TRUE(contains(r.out, std::string("nimbus ") + NIMBUS_E2E_VERSION)) << r.out;
}

TEST(Cli, RenderHelpExitsZero) {
  TestDir dir;
  const ProcessResult r = run_nimbus({"render", "--help"}, dir);
  EXPECT_TRUE(exited_with(r, 0)) << r.describe();
  EXPECT_TRUE(contains(r.out, "usage: nimbus render")) << r.out;
  EXPECT_TRUE(contains(r.out, "--iterations")) << r.out;
}

// One row of the `nimbus plugins` table: ID KIND VERSION STATUS PATH.
struct PluginRow {
  std::string id, kind, version, status;
};

std::vector<PluginRow> plugin_rows(const std::string &out) {
  std::vector<PluginRow> rows;
  std::istringstream lines(out);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream words(line);
    PluginRow row;
    std::string path;
    if (words >> row.id >> row.kind >> row.version >> row.status >> path && row.id != "ID")
      rows.push_back(row);
  }
  return rows;
}

TEST(Cli, PluginsListsTheBuiltInPluginsAsLoaded) {
  TestDir dir;
  const ProcessResult r = run_nimbus({"plugins"}, dir);
  EXPECT_TRUE(exited_with(r, 0)) << r.describe();
  const std::vector<PluginRow> rows = plugin_rows(r.out);
  const auto expect_loaded = [&](const std::string &id, const std::string &kind) {
    const auto it = std::find_if(rows.begin(), rows.end(), [&](const PluginRow &p) { return p.id == id; });
    ASSERT_NE(it, rows.end()) << id << " not listed:\n" << r.out;
    EXPECT_EQ(it->kind, kind) << r.out;
    EXPECT_EQ(it->status, "loaded") << r.out;
  };
  expect_loaded("nimbus.pt", "integrator");
  expect_loaded("nimbus.lights.power", "light-sampler");
}

}  // namespace cli_test
}  // namespace nimbus::e2e
