// `nimbus lightmix` end to end: the files it writes, the metadata it keeps and adds, its errors, a real
// LightMix render recombined at scale 1 coming back unchanged, and real nimbus.pt and nimbus.lt renders
// whose layers sum to beauty and relight by gains other than 1.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "e2e_support.hpp"
#include "lightmix_fixture.hpp"

namespace nimbus::e2e {
namespace lightmix_cli_test {

bool contains(const std::string &text, const std::string &part) {
  return text.find(part) != std::string::npos;
}

std::string write_input(const TestDir &dir, bool with_lightmix = true) {
  const std::string path = dir.file(with_lightmix ? "in.exr" : "plain.exr");
  EXPECT_TRUE(test::write_lightmix_exr(path, test::make_lightmix_image(), with_lightmix).ok());
  return path;
}

TEST(LightMixCli, WritesTheRelitExrAndPngWithMetadata) {
  TestDir dir;
  const std::string in = write_input(dir), out = dir.file("relit.exr");
  const ProcessResult r = run_nimbus({"lightmix", in, "--set", "key=0", "-o", out}, dir);
  ASSERT_TRUE(exited_with(r, 0)) << r.describe();
  EXPECT_TRUE(contains(r.err, "fill=1;key=0")) << r.err;
  EXPECT_TRUE(std::filesystem::exists(dir.file("relit.png")));
  EXPECT_EQ(dir.temporaries(), std::vector<std::string>{});

  const auto img = read_exr(out);
  ASSERT_TRUE(img);
  const test::LightMixImage src = test::make_lightmix_image();
  const std::vector<float> &g = plane(*img, "G");
  ASSERT_EQ(g.size(), size_t(test::kWidth) * test::kHeight);
  for (size_t p = 0; p < g.size(); ++p) {
    const size_t i = p * 3 + 1;
    EXPECT_NEAR(g[p], src.beauty[i] - src.key[i], 1e-6) << p;
  }
  for (float v : plane(*img, "lightmix.key.R")) EXPECT_EQ(v, 0.0f);
  EXPECT_EQ(plane(*img, "depth.Y").size(), g.size());
  EXPECT_EQ(meta_string(*img, "nimbus:lightmix"), std::optional<std::string>("fill=1;key=0"));
  EXPECT_EQ(meta_string(*img, "nimbus:lightmix_source"), std::optional<std::string>(in));
  EXPECT_EQ(meta_string(*img, "nimbus:scene"), std::optional<std::string>("synthetic.yaml"));
  EXPECT_EQ(meta_number(*img, "nimbus:iterations"), std::optional<double>(16));

  // Mixing the result again records both mixes, in order.
  const ProcessResult again = run_nimbus({"lightmix", out, "--set", "fill=2", "-o", out}, dir);
  ASSERT_TRUE(exited_with(again, 0)) << again.describe();
  const auto twice = read_exr(out);
  ASSERT_TRUE(twice);
  EXPECT_EQ(meta_string(*twice, "nimbus:lightmix"),
            std::optional<std::string>("fill=1;key=0 then fill=2;key=1"));
}

TEST(LightMixCli, ListPrintsTheGroups) {
  TestDir dir;
  const ProcessResult r = run_nimbus({"lightmix", write_input(dir), "--list"}, dir);
  ASSERT_TRUE(exited_with(r, 0)) << r.describe();
  EXPECT_EQ(r.out, "fill\nkey\n");
}

TEST(LightMixCli, ErrorsNameTheProblem) {
  TestDir dir;
  const std::string in = write_input(dir), plain = write_input(dir, false), out = dir.file("o.exr");
  struct Case {
    std::vector<std::string> args;
    int code;
    std::string message;
  };
  const std::vector<Case> cases = {
      {{"lightmix", dir.file("missing.exr"), "-o", out}, 1, dir.file("missing.exr")},
      {{"lightmix", plain, "-o", out}, 1, "no LightMix layers"},
      {{"lightmix", in, "--set", "rim=2", "-o", out}, 1, "unknown light group 'rim' (available: fill, key)"},
      {{"lightmix", in, "--set", "key", "-o", out}, 2, "malformed setting 'key'"},
      {{"lightmix", in, "--set", "key=-2", "-o", out}, 2, "malformed setting 'key=-2'"},
      {{"lightmix", in, "--set"}, 2, "--set: expected"},
      {{"lightmix", in, "--set", "key=2"}, 2, "no output given"},
      {{"lightmix", in, "-o", dir.file("o.png")}, 2, "its PNG preview is written beside it"},
      {{"lightmix", "-o", out}, 2, "no input image"},
      {{"lightmix", in, "--bogus", "-o", out}, 2, "unknown option '--bogus'"},
  };
  for (const Case &c : cases) {
    const ProcessResult r = run_nimbus(c.args, dir);
    EXPECT_TRUE(exited_with(r, c.code)) << c.message << ": " << r.describe();
    EXPECT_TRUE(contains(r.err, c.message)) << r.err;
  }
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(LightMixCli, RealRenderRecombinedAtScaleOneIsUnchanged) {
  TestDir dir;
  const std::string exr = dir.file("box.exr"), out = dir.file("mixed.exr");
  ProcessResult r = run_nimbus(
      {"render", scene("box.yaml"), "-o", exr, "-q", "--iterations", "2", "--elements", "lightmix"}, dir);
  ASSERT_TRUE(exited_with(r, 0)) << r.describe();
  r = run_nimbus({"lightmix", exr, "--list"}, dir);
  ASSERT_TRUE(exited_with(r, 0)) << r.describe();
  ASSERT_FALSE(r.out.empty());
  const std::string group = r.out.substr(0, r.out.find('\n'));
  r = run_nimbus({"lightmix", exr, "--set", group + "=1", "-o", out}, dir);
  ASSERT_TRUE(exited_with(r, 0)) << r.describe();
  const auto a = read_exr(exr), b = read_exr(out);
  ASSERT_TRUE(a && b);
  EXPECT_EQ(a->channels.size(), b->channels.size());
  for (const auto &[name, values] : a->channels) {
    const std::vector<float> &other = plane(*b, name);
    ASSERT_EQ(other.size(), values.size()) << name;
    for (size_t i = 0; i < values.size(); ++i)
      ASSERT_EQ(std::bit_cast<uint32_t>(values[i]), std::bit_cast<uint32_t>(other[i]))
          << name << "[" << i << "]";
  }
  EXPECT_EQ(meta_number(*b, "nimbus:iterations"), std::optional<double>(2));
}

// A room lit by a point light (group key) and an area lamp (group fill), rendered by `integrator` with
// the LightMix layers: beauty is the layers' sum, and relighting with key x2.5, fill x0 (tinted) gives
// 2.5 key, per pixel and channel, to float rounding (1e-5 relative: a few additions of positive terms).
void expect_layers_sum_and_relight(const std::string &integrator) {
  TestDir dir;
  const std::string yaml = dir.file("room.yaml"), exr = dir.file("room.exr"), out = dir.file("relit.exr");
  std::ofstream(yaml)
      << "render: { resolution: [24, 16], max_depth: 4 }\n"
         "camera: { position: [0, -3, 1], look_at: [0, 0, 0.8], up: [0, 0, 1], fov: 60 }\n"
         "materials:\n  white: { type: diffuse, albedo: [0.7, 0.6, 0.5] }\n"
         "  lamp: { type: diffuse, albedo: 0 }\n"
         "objects:\n  - { shape: rectangle, size: [6, 6], material: white }\n"
         "  - { shape: rectangle, size: [6, 3], material: white, transform: { rotate: [90, 0, 0], "
         "translate: [0, 2, 1.5] } }\n"
         "  - { shape: rectangle, size: [0.6, 0.6], material: lamp, emission: { radiance: [8, 9, 10] }, "
         "group: fill, transform: { rotate: [180, 0, 0], translate: [0.8, 0, 2.5] } }\n"
         "lights:\n  - { type: point, position: [-0.7, -0.5, 1.6], intensity: [3, 2, 1], group: key }\n";
  ProcessResult r = run_nimbus({"render", yaml, "-o", exr, "-q", "--iterations", "4", "--integrator",
                                integrator, "--elements", "lightmix"},
                               dir);
  ASSERT_TRUE(exited_with(r, 0)) << r.describe();
  r = run_nimbus({"lightmix", exr, "--set", "key=2.5", "--set", "fill=0,1,0.5,0.2", "-o", out}, dir);
  ASSERT_TRUE(exited_with(r, 0)) << r.describe();
  const auto img = read_exr(exr), relit = read_exr(out);
  ASSERT_TRUE(img && relit);
  double key_light = 0, fill_light = 0;
  for (const char *c : {"R", "G", "B"}) {
    const std::vector<float> &beauty = plane(*img, c), &key = plane(*img, std::string("lightmix.key.") + c),
                             &fill = plane(*img, std::string("lightmix.fill.") + c),
                             &mixed = plane(*relit, c);
    ASSERT_EQ(key.size(), beauty.size());
    ASSERT_EQ(fill.size(), beauty.size());
    ASSERT_EQ(mixed.size(), beauty.size());
    for (size_t i = 0; i < beauty.size(); ++i) {
      EXPECT_NEAR(beauty[i], key[i] + fill[i], 1e-5 * std::abs(beauty[i]) + 1e-7)
          << integrator << " " << c << i;
      EXPECT_NEAR(mixed[i], 2.5 * key[i], 1e-5 * std::abs(2.5 * key[i]) + 1e-7)
          << integrator << " " << c << i;
      key_light += key[i], fill_light += fill[i];
    }
  }
  // Both groups light the room, so neither check holds by a layer being empty.
  EXPECT_GT(key_light, 0.1 * fill_light) << integrator;
  EXPECT_GT(fill_light, 0.1 * key_light) << integrator;
}

TEST(LightMixCli, PathTracerLayersSumToBeautyAndRelight) { expect_layers_sum_and_relight("pt"); }
TEST(LightMixCli, LightTracerLayersSumToBeautyAndRelight) { expect_layers_sum_and_relight("lt"); }

}  // namespace lightmix_cli_test
}  // namespace nimbus::e2e
