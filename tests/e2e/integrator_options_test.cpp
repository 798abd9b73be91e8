// Options the bound integrator declares, end to end: the scene's render keys and the command line's
// --NAME flags are checked against the declarations once the integrator is bound (errors name the place,
// the plugin and its options), and `nimbus plugins --options ID` prints them. The host knows no option.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <regex>

#include "e2e_support.hpp"

namespace nimbus::e2e {
namespace {

bool contains(const std::string &text, const std::string &part) {
  return text.find(part) != std::string::npos;
}

// box.yaml with its `integrator:` line replaced by `lines` (written into the render section).
std::string box_with(const TestDir &dir, const std::string &lines) {
  std::string text = read_bytes(scene("box.yaml"));
  const std::string from = "  integrator: nimbus.pt\n";
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos);
  text.replace(at, from.size(), lines);
  const std::string path = dir.file("scene.yaml");
  write_bytes(path, text);
  return path;
}

// The 1-based line of `needle` in the file at `path`.
int line_of(const std::string &path, const std::string &needle) {
  const std::string text = read_bytes(path);
  return 1 + int(std::count(text.begin(), text.begin() + ptrdiff_t(text.find(needle)), '\n'));
}

TEST(IntegratorOptions, SwitchForAnIntegratorWithoutItNamesBoth) {
  TestDir dir;
  const ProcessResult r =
      run_nimbus({"render", scene("box.yaml"), "--caustics", "on", "-q", "-o", dir.file("x.exr")}, dir);
  EXPECT_TRUE(exited_with(r, 1)) << r.describe();
  EXPECT_TRUE(contains(r.err, "--caustics: nimbus.pt has no option 'caustics' (it declares no options)"))
      << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("x.exr")));
}

TEST(IntegratorOptions, BadSceneValueNamesFileLineColumnAndTheValues) {
  TestDir dir;
  const std::string path = box_with(dir, "  integrator: caustics\n  caustics: maybe\n");
  const ProcessResult r = run_nimbus({"render", path, "-q", "-o", dir.file("x.exr")}, dir);
  EXPECT_TRUE(exited_with(r, 1)) << r.describe();
  const std::string where =
      path + ":" + std::to_string(line_of(path, "caustics: maybe")) + ":3: render.caustics";
  EXPECT_TRUE(contains(r.err, where + ": nimbus.caustics option 'caustics' expects on|off, got 'maybe'"))
      << r.err;
}

TEST(IntegratorOptions, UnknownRenderKeyListsTheIntegratorsOptionsAndTheHostKeys) {
  TestDir dir;
  const std::string path = box_with(dir, "  integrator: caustics\n  threads: 4\n");
  const ProcessResult r = run_nimbus({"render", path, "-q", "-o", dir.file("x.exr")}, dir);
  EXPECT_TRUE(exited_with(r, 1)) << r.describe();
  EXPECT_TRUE(contains(
      r.err,
      "render.threads: nimbus.caustics has no option 'threads' (its options: caustics, photon_emission, "
      "photon_light_selection, photon_times); "
      "the render section's own keys: resolution, iterations"))
      << r.err;
}

// A guide the scene or the command line names must be installed: the error names where it was named.
TEST(IntegratorOptions, MissingNamedGuideNamesFileLineColumn) {
  TestDir dir;
  const std::string path = box_with(dir, "  integrator: caustics\n  guide: org.example.missing\n");
  ProcessResult r = run_nimbus({"render", path, "-q", "-o", dir.file("x.exr")}, dir);
  EXPECT_TRUE(exited_with(r, 1)) << r.describe();
  const std::string where =
      path + ":" + std::to_string(line_of(path, "guide: org.example.missing")) + ":10: render.guide: ";
  EXPECT_TRUE(contains(r.err, where)) << r.err;
  EXPECT_TRUE(contains(r.err, "org.example.missing")) << r.err;
  r = run_nimbus({"render", path, "--guide", "org.example.other", "-q", "-o", dir.file("x.exr")}, dir);
  EXPECT_TRUE(exited_with(r, 1)) << r.describe();
  EXPECT_TRUE(contains(r.err, "--guide: ")) << r.err;
  EXPECT_TRUE(contains(r.err, "org.example.other")) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("x.exr")));
}

TEST(IntegratorOptions, CommandLineOverridesTheSceneAndIsRecorded) {
  TestDir dir;
  const std::string path = box_with(dir, "  integrator: caustics\n  caustics: on\n");
  const ProcessResult r =
      run_nimbus({"render", path, "--caustics=OFF", "--iterations", "1", "-q", "-o", dir.file("x.exr")}, dir);
  ASSERT_TRUE(exited_with(r, 0)) << r.describe();
  // The checkpoint's fingerprint holds the resolved options, normalised.
  EXPECT_TRUE(contains(read_bytes(dir.file("x.exr.ckpt")), "options=caustics:off")) << "no resolved options";
}

TEST(IntegratorOptions, PluginsCommandPrintsTheDeclarations) {
  TestDir dir;
  const ProcessResult c = run_nimbus({"plugins", "--options", "caustics"}, dir);
  EXPECT_TRUE(exited_with(c, 0)) << c.describe();
  EXPECT_TRUE(std::regex_search(c.out, std::regex(R"(\n  caustics +on\|off +on +\S)"))) << c.out;
  const ProcessResult pt = run_nimbus({"plugins", "--options", "nimbus.pt"}, dir);
  EXPECT_TRUE(exited_with(pt, 0)) << pt.describe();
  EXPECT_TRUE(contains(pt.out, "nimbus.pt declares no options")) << pt.out;
  const ProcessResult none = run_nimbus({"plugins", "--options", "org.example.none"}, dir);
  EXPECT_TRUE(exited_with(none, 1)) << none.describe();
  EXPECT_TRUE(contains(none.err, "org.example.none")) << none.err;
}

}  // namespace
}  // namespace nimbus::e2e

namespace nimbus::e2e {
namespace {

// The shipped default scene at 96 x 96: it names no integrator, so the caustics solver renders it (with
// photons: it has a glass sphere); `--caustics off` renders exactly what `--integrator pt` renders.
TEST(IntegratorOptions, CausticsSolverIsTheDefaultAndOffIsThePathTracer) {
  TestDir dir;
  const std::filesystem::path shipped =
      std::filesystem::path(scene("box.yaml")).parent_path() / "../../../scenes/default.yaml";
  std::string text = read_bytes(shipped.string());
  ASSERT_EQ(text.find("integrator:"), std::string::npos) << "the default scene must not pick an integrator";
  const std::string from = "resolution: [512, 512]";
  ASSERT_NE(text.find(from), std::string::npos);
  text.replace(text.find(from), from.size(), "resolution: [96, 96]");
  const std::string path = dir.file("default.yaml");
  write_bytes(path, text);
  const auto render = [&](std::vector<std::string> extra, const std::string &out) {
    std::vector<std::string> args = {"render", path, "--iterations", "2", "-q", "-o", dir.file(out)};
    args.insert(args.end(), extra.begin(), extra.end());
    const ProcessResult r = run_nimbus(args, dir);
    EXPECT_TRUE(exited_with(r, 0)) << r.describe();
    auto img = read_exr(dir.file(out));
    EXPECT_TRUE(img.has_value());
    return img ? *img : ImageLayers{};
  };
  const ImageLayers on = render({}, "on.exr"), off = render({"--caustics", "off"}, "off.exr"),
                    pt = render({"--integrator", "pt"}, "pt.exr");
  EXPECT_EQ(meta_string(on, "nimbus:integrator"), "nimbus.caustics");
  EXPECT_GT(meta_number(on, "nimbus:stat:caustics_photons").value_or(0), 0) << "no photon stored";
  EXPECT_EQ(meta_string(off, "nimbus:integrator"), "nimbus.caustics");
  EXPECT_EQ(plane(off, "R"), plane(pt, "R"));
  EXPECT_EQ(plane(off, "B"), plane(pt, "B"));
  EXPECT_NE(plane(on, "R"), plane(pt, "R"));
}

}  // namespace
}  // namespace nimbus::e2e
