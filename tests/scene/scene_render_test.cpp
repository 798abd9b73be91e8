// `render:` keys of format v1: pixel filter, render region, light sampler and error target.
#include <gtest/gtest.h>

#include "scene_test_support.hpp"

namespace nimbus::test {
namespace scene_render_test {

TEST(SceneRender, FilterRegionSamplerAndTargetError) {
  const SceneDesc scene = parse_ok(R"(render:
  region: [10, 20, 110, 220]
  resolution: [640, 360]
  filter: blackman-harris
  light_sampler: nimbus.lights.tree
  target_error: 0.01
)");
  const RenderDesc &r = scene.render;
  EXPECT_EQ(r.filter, FilterType::BlackmanHarris);
  // Checked against the resolution even though `region` comes first.
  EXPECT_EQ(std::vector<uint32_t>(r.region, r.region + 4), (std::vector<uint32_t>{10, 20, 110, 220}));
  EXPECT_EQ(r.light_sampler, "nimbus.lights.tree");
  EXPECT_DOUBLE_EQ(r.target_error, 0.01);
}

TEST(SceneRender, DefaultsOfTheV1Keys) {
  const RenderDesc r = parse_ok("render: { seed: 2 }\n").render;
  EXPECT_EQ(r.filter, FilterType::Box);
  EXPECT_EQ(std::vector<uint32_t>(r.region, r.region + 4), (std::vector<uint32_t>{0, 0, 0, 0}));
  EXPECT_EQ(r.light_sampler, "");
  EXPECT_EQ(r.target_error, 0);
}

TEST(SceneRender, EveryFilterAndAWholeImageRegion) {
  for (const char *filter : {"box", "gaussian", "blackman-harris"})
    EXPECT_EQ(filter_name(parse_ok(std::string("render: { filter: ") + filter + " }\n").render.filter),
              filter);
  const RenderDesc r = parse_ok("render: { resolution: [64, 32], region: [0, 0, 64, 32] }\n").render;
  EXPECT_EQ(r.region[2], 64u);
  EXPECT_EQ(r.region[3], 32u);
}

TEST(SceneRenderErrors, UnknownFilter) {
  EXPECT_TRUE(fails_at("render:\n  filter: mitchell\n", 2, 11, "render.filter",
                       "unknown pixel filter 'mitchell'; known: box, gaussian, blackman-harris"));
}

TEST(SceneRenderErrors, RegionOutsideTheImage) {
  EXPECT_TRUE(fails_at("render:\n  resolution: [64, 32]\n  region: [0, 0, 65, 32]\n", 3, 18,
                       "render.region[2]", "must be in [0, 64] (got 65)"));
  // Without `resolution:` the default 512 x 512 applies.
  EXPECT_TRUE(fails_at("render:\n  region: [0, 0, 10, 513]\n", 2, 22, "render.region[3]",
                       "must be in [0, 512] (got 513)"));
}

TEST(SceneRenderErrors, EmptyRegion) {
  EXPECT_TRUE(fails_at("render:\n  region: [10, 10, 10, 20]\n", 2, 20, "render.region[2]",
                       "x1 must be greater than x0 (got 10)"));
  EXPECT_TRUE(fails_at("render:\n  region: [0, 20, 10, 5]\n", 2, 23, "render.region[3]",
                       "y1 must be greater than y0 (got 20)"));
}

TEST(SceneRenderErrors, RegionOfWrongShape) {
  EXPECT_TRUE(fails_at("render:\n  region: [0, 0, 10]\n", 2, 11, "render.region",
                       "expected [x0, y0, x1, y1] (4 elements), got 3 elements"));
  EXPECT_TRUE(fails_at("render:\n  region: [0, 0, 10.5, 4]\n", 2, 18, "render.region[2]",
                       "expected an integer, got 10.5"));
}

TEST(SceneRenderErrors, TargetErrorMustBePositive) {
  EXPECT_TRUE(fails_at("render:\n  target_error: 0\n", 2, 17, "render.target_error", "must be > 0 (got 0)"));
}

TEST(SceneRenderErrors, EmptyLightSampler) {
  EXPECT_TRUE(
      fails_at("render:\n  light_sampler: \"\"\n", 2, 18, "render.light_sampler", "must not be empty"));
}

}  // namespace scene_render_test
}  // namespace nimbus::test
