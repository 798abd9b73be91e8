// `nimbus render` of a tiny scene, checked through its output files only: the EXR's pixels and header and
// the PNG preview beside it.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "e2e_support.hpp"

namespace nimbus::e2e {
namespace render_output_test {

constexpr int kWidth = 64, kHeight = 48;  // tests/e2e/scenes/box.yaml

TEST(RenderOutput, TinySceneWritesExrWithMetadataAndPngPreview) {
  TestDir dir;
  const std::string exr = dir.file("box.exr");
  // Iterations and seed come from the scene (4 and 7), so the header proves the scene's values are used.
  const ProcessResult r = run_nimbus({"render", scene("box.yaml"), "-o", exr}, dir);
  ASSERT_TRUE(exited_with(r, 0)) << r.describe();

  const auto img = read_exr(exr);
  ASSERT_TRUE(img);
  EXPECT_EQ(img->width, uint32_t(kWidth));
  EXPECT_EQ(img->height, uint32_t(kHeight));
  double sum = 0;
  for (const char *c : {"R", "G", "B"}) {
    const std::vector<float> &p = plane(*img, c);
    ASSERT_EQ(p.size(), size_t(kWidth) * kHeight) << c;
    for (size_t i = 0; i < p.size(); ++i)
      ASSERT_TRUE(std::isfinite(p[i])) << c << " pixel " << i << " = " << p[i];
    sum += std::accumulate(p.begin(), p.end(), 0.0);
    // A lit box is not a flat image: catches a film filled with one value.
    const auto [lo, hi] = std::minmax_element(p.begin(), p.end());
    EXPECT_LT(*lo, *hi) << c;
  }
  EXPECT_GT(sum / (3.0 * kWidth * kHeight), 0.0);

  EXPECT_EQ(meta_string(*img, "nimbus:version"), std::optional<std::string>(NIMBUS_E2E_VERSION));
  EXPECT_EQ(meta_string(*img, "nimbus:integrator"), std::optional<std::string>("nimbus.pt"));
  EXPECT_EQ(meta_string(*img, "nimbus:stopped_by"), std::optional<std::string>("iterations"));
  EXPECT_EQ(meta_number(*img, "nimbus:iterations"), std::optional<double>(4));
  EXPECT_EQ(recorded_seed(*img), std::optional<uint64_t>(7));
  const std::optional<double> seconds = meta_number(*img, "nimbus:seconds");
  ASSERT_TRUE(seconds) << "nimbus:seconds missing";
  EXPECT_TRUE(std::isfinite(*seconds) && *seconds >= 0) << *seconds;
  // The time to first pixel and its parts: loading, setting up, the first of the 4 iterations.
  const auto load = meta_number(*img, "nimbus:load_seconds"),
             setup = meta_number(*img, "nimbus:setup_seconds"),
             first = meta_number(*img, "nimbus:first_iteration_seconds"),
             ttfp = meta_number(*img, "nimbus:time_to_first_pixel");
  ASSERT_TRUE(load && setup && first && ttfp) << "time to first pixel missing";
  EXPECT_GT(*load, 0);
  EXPECT_GT(*setup, 0);
  EXPECT_GT(*first, 0);
  EXPECT_LE(*first, *seconds);
  EXPECT_NEAR(*ttfp, *load + *setup + *first, 1e-9 * *ttfp);

  // The preview: same stem, 8-bit RGB, same size, not black.
  const std::string png = dir.file("box.png");
  auto in = OIIO::ImageInput::open(png);
  ASSERT_TRUE(in) << png << ": " << OIIO::geterror();
  const OIIO::ImageSpec &spec = in->spec();
  EXPECT_EQ(spec.width, kWidth);
  EXPECT_EQ(spec.height, kHeight);
  EXPECT_EQ(spec.nchannels, 3);
  EXPECT_EQ(spec.format, OIIO::TypeDesc::UINT8);
  std::vector<uint8_t> px(size_t(spec.width) * spec.height * spec.nchannels);
  ASSERT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, px.data())) << in->geterror();
  EXPECT_GT(std::accumulate(px.begin(), px.end(), 0.0), 0.0);
  in->close();

  // Exactly the outputs (image, preview, checkpoint): no temporaries left behind by the atomic writes.
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"box.exr", "box.exr.ckpt", "box.png"}));
}

TEST(RenderOutput, QuietRenderPrintsNothing) {
  TestDir dir;
  const ProcessResult r = run_nimbus({"render", scene("box.yaml"), "-o", dir.file("q.exr"), "-q"}, dir);
  ASSERT_TRUE(exited_with(r, 0)) << r.describe();
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(r.out, "");
  EXPECT_TRUE(std::filesystem::exists(dir.file("q.exr")));
  EXPECT_TRUE(std::filesystem::exists(dir.file("q.png")));
}

}  // namespace render_output_test
}  // namespace nimbus::e2e

namespace nimbus::e2e {
namespace render_output_test {

// The command line's stopping rules replace the scene's: `--time` on a scene that says `iterations: 4`
// renders until the time is up (more than 4 iterations of this tiny scene in 1.5 s on any machine that
// runs the suite), not until whichever comes first.
TEST(RenderOutput, CommandLineTimeReplacesTheScenesIterations) {
  TestDir dir;
  const std::string exr = dir.file("t.exr");
  const ProcessResult r = run_nimbus({"render", scene("box.yaml"), "-o", exr, "--time", "1.5", "-q"}, dir);
  ASSERT_TRUE(exited_with(r, 0)) << r.describe();
  const auto img = read_exr(exr);
  ASSERT_TRUE(img);
  EXPECT_EQ(meta_string(*img, "nimbus:stopped_by"), std::optional<std::string>("time"));
  const std::optional<double> iterations = meta_number(*img, "nimbus:iterations");
  ASSERT_TRUE(iterations);
  EXPECT_GT(*iterations, 4);
}

}  // namespace render_output_test
}  // namespace nimbus::e2e
