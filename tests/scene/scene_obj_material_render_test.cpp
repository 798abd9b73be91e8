// The room fixture rendered with its .mtl materials and no `material:`: in process, the red wall comes out
// red and the back wall shows its map_Kd image, lit by the lamp's Ke alone; through the CLI, the scene
// renders and its warning is printed once.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <sstream>

#include "e2e/subprocess.hpp"
#include "obj_material_support.hpp"
#include "support/render_support.hpp"

namespace nimbus::test {
namespace scene_obj_material_render_test {

using nimbus::testing::region_mean;

constexpr int kSize = 32;

TEST(SceneObjMaterialRender, TheRedWallIsRedAndTheBackWallShowsItsImage) {
  // room_scene.yaml with the mesh's absolute path, since inline scenes resolve against the current directory.
  std::ifstream in(kRoomDir + "/room_scene.yaml");
  std::stringstream text;
  text << in.rdbuf();
  std::string yaml = text.str();
  yaml.replace(yaml.find("file: room.obj"), 14, "file: " + kRoomObj);

  nimbus::testing::SceneRenderer renderer;
  nimbus::testing::RenderRequest request;
  request.integrator = "nimbus.pt";
  request.iterations = 16;
  request.threads = 1;
  const ImageLayers img = renderer.render(yaml, request);
  ASSERT_EQ(img.width, uint32_t(kSize));

  // The camera at y = -3.5 looks along +y at the room's middle: the left wall (x = -1) fills the image's
  // left fifth; the back wall (y = 1) the middle half, its upper right quarter a blue texel of the checker.
  const Rgb red = region_mean(img, 1, 6, 12, 20);
  EXPECT_GT(red.x, 0.02f);
  EXPECT_GT(red.x, 2 * red.y) << red.x << " " << red.y << " " << red.z;
  EXPECT_GT(red.x, 2 * red.z) << red.x << " " << red.y << " " << red.z;
  const Rgb blue = region_mean(img, 18, 22, 10, 14), white = region_mean(img, 10, 14, 10, 14);
  EXPECT_GT(blue.z, 2 * blue.x) << blue.x << " " << blue.y << " " << blue.z;
  EXPECT_LT(white.z, 1.5f * white.x) << white.x << " " << white.y << " " << white.z;
}

TEST(SceneObjMaterialRender, TheCliRendersTheFixtureAndWarnsOnce) {
  const TempDir dir;
  const e2e::ProcessResult r = e2e::run_process({NIMBUS_CLI, "render", kRoomDir + "/room_scene.yaml", "-o",
                                                 "out.exr", "--iterations", "1", "--threads", "1", "-q"},
                                                dir.path());
  EXPECT_TRUE(r.exited && r.exit_code == 0) << r.describe();
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "out.exr"));
  const std::string room_scene = kRoomDir + "/room_scene.yaml";
  EXPECT_EQ(r.err, room_scene + ":5:26: warning: objects[0].file: " + kRoomDir +
                       "/room.mtl: ignores the .mtl statements Nimbus does not map: map_Kd -s, map_Bump, Pr, "
                       "sharpness\n");
}

}  // namespace scene_obj_material_render_test
}  // namespace nimbus::test
