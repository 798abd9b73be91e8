// `nimbus compare` end to end: text and JSON output on images with a known error, --element, --heatmap,
// and the errors that stop a comparison.
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>

#include "e2e_support.hpp"
#include "film/film.hpp"

namespace nimbus::e2e {
namespace compare_cli_test {

constexpr uint32_t kW = 5, kH = 3;

bool contains(const std::string &text, const std::string &part) {
  return text.find(part) != std::string::npos;
}

// An EXR with beauty = `beauty` everywhere, albedo = 0.5 everywhere and depth = 2.
std::string write_image(const TestDir &dir, const std::string &name, float beauty, uint32_t w = kW,
                        uint32_t h = kH) {
  const std::vector<float> rgb(size_t(w) * h * 3, beauty), albedo(size_t(w) * h * 3, 0.5f),
      depth(size_t(w) * h, 2.0f);
  const std::string path = dir.file(name);
  const Status s = write_layered_exr(path, w, h,
                                     {{{"R", "G", "B"}, rgb.data()},
                                      {{"albedo.R", "albedo.G", "albedo.B"}, albedo.data()},
                                      {{"depth.Y"}, depth.data()}},
                                     {}, {});
  EXPECT_TRUE(s.ok()) << s.error().message;
  return path;
}

// The number after `"key": ` in a one-line JSON object.
double json_number(const std::string &json, const std::string &key) {
  std::smatch m;
  if (!std::regex_search(json, m, std::regex("\"" + key + "\": ([-0-9.eE+]+)"))) {
    ADD_FAILURE() << key << " not in " << json;
    return -1;
  }
  return std::stod(m[1]);
}

TEST(CompareCli, TextReportsEveryMetric) {
  TestDir dir;
  const std::string t = write_image(dir, "t.exr", 1.5f), r = write_image(dir, "r.exr", 1.0f);
  const ProcessResult p = run_nimbus({"compare", t, r}, dir);
  ASSERT_TRUE(exited_with(p, 0)) << p.describe();
  for (const char *line :
       {"RMSE         0.5\n", "relMSE       0.247525\n", "relMSE (Y)   0.247525\n", "MAPE         0.49505\n",
        "NaN/Inf pixels in TEST: 0", "element    beauty (3 channels, 5x3)"})
    EXPECT_TRUE(contains(p.out, line)) << line << " not in:\n" << p.out;
}

TEST(CompareCli, JsonIsMachineReadable) {
  TestDir dir;
  const std::string t = write_image(dir, "t.exr", 1.5f), r = write_image(dir, "r.exr", 1.0f);
  const ProcessResult p = run_nimbus({"compare", t, r, "--json"}, dir);
  ASSERT_TRUE(exited_with(p, 0)) << p.describe();
  EXPECT_EQ(p.out.front(), '{');
  EXPECT_EQ(p.out.substr(p.out.size() - 2), "}\n");
  EXPECT_DOUBLE_EQ(json_number(p.out, "rmse"), 0.5);
  EXPECT_NEAR(json_number(p.out, "relmse"), 0.25 / 1.01, 1e-8);
  EXPECT_NEAR(json_number(p.out, "relmse_luminance"), 0.25 / 1.01, 1e-8);
  EXPECT_NEAR(json_number(p.out, "mape"), 0.5 / 1.01, 1e-8);
  EXPECT_EQ(json_number(p.out, "nonfinite_test"), 0);
  EXPECT_EQ(json_number(p.out, "compared_pixels"), kW * kH);
  EXPECT_TRUE(contains(p.out, "\"element\": \"beauty\"")) << p.out;
  EXPECT_TRUE(contains(p.out, "\"heatmap\": null")) << p.out;
}

TEST(CompareCli, ElementSelectsTheLayer) {
  TestDir dir;
  const std::string t = write_image(dir, "t.exr", 1.5f), r = write_image(dir, "r.exr", 1.0f);
  for (const char *element : {"albedo", "depth"}) {
    const ProcessResult p = run_nimbus({"compare", t, r, "--element", element, "--json"}, dir);
    ASSERT_TRUE(exited_with(p, 0)) << p.describe();
    EXPECT_EQ(json_number(p.out, "rmse"), 0) << element;  // beauty differs, these do not
    EXPECT_EQ(json_number(p.out, "channels"), std::string(element) == "depth" ? 1 : 3);
  }
}

TEST(CompareCli, HeatmapIsWrittenAndItsLegendPrinted) {
  TestDir dir;
  const std::string t = write_image(dir, "t.exr", 1.5f), r = write_image(dir, "r.exr", 1.0f);
  const std::string heat = dir.file("heat.png");
  const ProcessResult p = run_nimbus({"compare", t, r, "--heatmap", heat}, dir);
  ASSERT_TRUE(exited_with(p, 0)) << p.describe();
  EXPECT_TRUE(std::filesystem::exists(heat));
  EXPECT_TRUE(contains(p.out, "heatmap    " + heat + ": per-pixel relative squared error")) << p.out;
  EXPECT_TRUE(contains(p.out, "viridis")) << p.out;
}

TEST(CompareCli, ErrorsExitNonZeroAndSayWhy) {
  TestDir dir;
  const std::string t = write_image(dir, "t.exr", 1.5f), r = write_image(dir, "r.exr", 1.0f);
  const std::string small = write_image(dir, "small.exr", 1.0f, 4, 3);
  struct Case {
    std::vector<std::string> args;
    int code;
    std::string message;
  };
  const std::vector<Case> cases = {
      {{"compare", t, small}, 1, "differ in size: '" + t + "' is 5x3, '" + small + "' is 4x3"},
      {{"compare", t, dir.file("none.exr")}, 1, dir.file("none.exr")},
      {{"compare", t, r, "--element", "normal"},
       1,
       "has no layer 'normal' (available: albedo, beauty, depth)"},
      {{"compare", t}, 2, "expected two images"},
      {{"compare", t, r, r}, 2, "expected two images"},
      {{"compare", t, r, "--element"}, 2, "--element: expected a layer name"},
      {{"compare", t, r, "--fast"}, 2, "unknown option '--fast'"},
  };
  for (const Case &c : cases) {
    const ProcessResult p = run_nimbus(c.args, dir);
    EXPECT_TRUE(exited_with(p, c.code)) << c.message << ": " << p.describe();
    EXPECT_TRUE(contains(p.err, c.message)) << p.err;
  }
}

}  // namespace compare_cli_test
}  // namespace nimbus::e2e
