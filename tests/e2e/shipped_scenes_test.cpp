// Every scene shipped in scenes/ renders with its own integrator (the caustics solver unless it names
// another): a few iterations of a corner, so that a scene whose lights, materials or sizes trip a plugin
// (lights six decades apart in power, a kilometre-wide stadium, a thousand bulbs) fails here, not in a
// user's hands. Include files (scenes/caustics/assets/) are not scenes.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "e2e_support.hpp"

namespace nimbus::e2e {
namespace shipped_scenes_test {

TEST(ShippedScenes, EveryOneRendersWithItsOwnIntegrator) {
  std::vector<std::filesystem::path> scenes;
  for (const auto &entry : std::filesystem::recursive_directory_iterator(NIMBUS_SHIPPED_SCENES))
    if (entry.path().extension() == ".yaml" && entry.path().parent_path().filename() != "assets")
      scenes.push_back(entry.path());
  std::sort(scenes.begin(), scenes.end());
  ASSERT_GE(scenes.size(), 15u) << NIMBUS_SHIPPED_SCENES;
  for (const auto &path : scenes) {
    TestDir dir;
    const ProcessResult r = run_nimbus({"render", path.string(), "-o", dir.file("out.exr"), "--iterations",
                                        "3", "--region", "0,0,48,32", "--threads", "2", "-q"},
                                       dir);
    EXPECT_TRUE(exited_with(r, 0)) << path << "\n" << r.err;
    if (exited_with(r, 0)) {
      const auto img = read_exr(dir.file("out.exr"));
      ASSERT_TRUE(img) << path;
      EXPECT_EQ(meta_number(*img, "nimbus:iterations").value_or(0), 3.0) << path;
    }
  }
}

}  // namespace shipped_scenes_test
}  // namespace nimbus::e2e
