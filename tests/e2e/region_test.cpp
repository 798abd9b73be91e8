// Render regions (crop windows) through the CLI: `--region` and the scene's `render.region` render only
// that rectangle of the full-size image and leave the rest black. Camera samples draw their random numbers
// from (seed, pixel, iteration), so with nimbus.pt the region's pixels are those of the whole frame bit for
// bit. The caustics solver sizes its photon passes by the frame but spends photons per camera path of the
// region (plugins/caustics/README.md), so its regions promise the black outside and photons, not bits.
#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "e2e_support.hpp"

namespace nimbus::e2e {
namespace region_test {

constexpr uint32_t kWidth = 64, kHeight = 48;  // box.yaml
// Not on the 32-pixel tile grid, so that clipped tiles are exercised.
constexpr uint32_t kRegion[4] = {9, 5, 41, 30};

std::string region_flag() {
  return std::to_string(kRegion[0]) + "," + std::to_string(kRegion[1]) + "," + std::to_string(kRegion[2]) +
         "," + std::to_string(kRegion[3]);
}

bool inside(uint32_t x, uint32_t y) {
  return x >= kRegion[0] && x < kRegion[2] && y >= kRegion[1] && y < kRegion[3];
}

ImageLayers render_box(const TestDir &dir, const std::string &scene_path, const std::string &out,
                       std::vector<std::string> extra = {}) {
  std::vector<std::string> args = {"render", scene_path, "-q", "-o", dir.file(out)};
  args.insert(args.end(), extra.begin(), extra.end());
  const ProcessResult r = run_nimbus(args, dir);
  EXPECT_TRUE(exited_with(r, 0)) << r.describe();
  auto img = read_exr(dir.file(out));
  return img ? *img : ImageLayers{};
}

// Counts the pixels of `region` whose bits differ from `full`'s, and those outside that are not +0.
void compare_planes(const ImageLayers &region, const ImageLayers &full, size_t &differ, size_t &lit_outside) {
  static constexpr float kZero = 0.0f;
  differ = lit_outside = 0;
  for (const char *c : {"R", "G", "B"}) {
    const std::vector<float> &a = plane(region, c), &b = plane(full, c);
    ASSERT_EQ(a.size(), size_t(kWidth) * kHeight);
    ASSERT_EQ(b.size(), a.size());
    for (uint32_t y = 0; y < kHeight; ++y)
      for (uint32_t x = 0; x < kWidth; ++x) {
        const size_t i = size_t(y) * kWidth + x;
        if (inside(x, y))
          differ += std::memcmp(&a[i], &b[i], sizeof(float)) != 0;
        else
          lit_outside += std::memcmp(&a[i], &kZero, sizeof(float)) != 0;
      }
  }
}

TEST(RenderRegion, RegionIsTheFullFramesPixelsAndTheRestIsBlack) {
  TestDir dir;
  const std::string box = scene("box.yaml");
  const std::string flag = region_flag();
  const ImageLayers full = render_box(dir, box, "full.exr");
  const ImageLayers cropped = render_box(dir, box, "region.exr", {"--region", flag});
  ASSERT_EQ(cropped.width, kWidth);  // the full image's size, not the region's
  ASSERT_EQ(cropped.height, kHeight);
  size_t differ = 0, lit_outside = 0;
  compare_planes(cropped, full, differ, lit_outside);
  EXPECT_EQ(differ, 0u) << "region pixels that differ from the full frame's";
  EXPECT_EQ(lit_outside, 0u) << "pixels outside the region that are not black";
  // The full frame is lit inside the region (so the comparison compares something).
  double sum = 0;
  for (uint32_t y = kRegion[1]; y < kRegion[3]; ++y)
    for (uint32_t x = kRegion[0]; x < kRegion[2]; ++x) sum += plane(full, "G")[size_t(y) * kWidth + x];
  EXPECT_GT(sum, 0.0);
  // The header says how the image was made; the whole frame has no region.
  EXPECT_EQ(meta_string(cropped, "nimbus:region"), flag);
  EXPECT_EQ(meta_string(full, "nimbus:region"), std::nullopt);
  EXPECT_EQ(meta_string(cropped, "nimbus:filter"), "box");
  EXPECT_EQ(meta_number(cropped, "nimbus:iterations"), meta_number(full, "nimbus:iterations"));
  EXPECT_EQ(recorded_seed(cropped), recorded_seed(full));
  // Fewer camera rays: about the region's share of the frame's (32 x 25 of 64 x 48).
  const double share =
      meta_number(cropped, "nimbus:rays").value_or(0) / meta_number(full, "nimbus:rays").value_or(1);
  EXPECT_GT(share, 0.1);
  EXPECT_LT(share, 0.5);

  // The scene's key renders the same image as the flag.
  std::string text = read_bytes(box);
  const std::string from = "  integrator: nimbus.pt\n";
  ASSERT_NE(text.find(from), std::string::npos);
  text.replace(text.find(from), from.size(), from + "  region: [" + flag + "]\n");
  write_bytes(dir.file("box_region.yaml"), text);
  const ImageLayers keyed = render_box(dir, dir.file("box_region.yaml"), "keyed.exr");
  for (const char *c : {"R", "G", "B"}) EXPECT_EQ(plane(keyed, c), plane(cropped, c)) << c;
  EXPECT_EQ(meta_string(keyed, "nimbus:region"), flag);
}

// The caustics solver renders a region with photons (box.yaml has a glass sphere under an area light)
// and leaves the rest black.
TEST(RenderRegion, CausticsSolverRendersTheRegionWithPhotons) {
  TestDir dir;
  const std::string flag = region_flag();
  const ImageLayers img =
      render_box(dir, scene("box.yaml"), "caustics.exr", {"--integrator", "caustics", "--region", flag});
  ASSERT_EQ(img.width, kWidth);
  EXPECT_EQ(meta_string(img, "nimbus:integrator"), "nimbus.caustics");
  EXPECT_GT(meta_number(img, "nimbus:stat:caustics_photons").value_or(0), 0) << "no photon stored";
  double inside_sum = 0;
  size_t lit_outside = 0;
  for (const char *c : {"R", "G", "B"}) {
    const std::vector<float> &p = plane(img, c);
    ASSERT_EQ(p.size(), size_t(kWidth) * kHeight);
    for (uint32_t y = 0; y < kHeight; ++y)
      for (uint32_t x = 0; x < kWidth; ++x) {
        const float v = p[size_t(y) * kWidth + x];
        if (inside(x, y))
          inside_sum += v;
        else
          lit_outside += v != 0.0f;
      }
  }
  EXPECT_GT(inside_sum, 0.0);
  EXPECT_EQ(lit_outside, 0u);
}

}  // namespace region_test
}  // namespace nimbus::e2e
