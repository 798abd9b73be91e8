// The CLI without its image I/O module (core/image_io.hpp): a copy of the executable in a prefix that
// has the build's plugins but no lib/nimbus/host/. Commands that read no image still work, renders
// included (the film writes with OpenEXR and libpng); one that reads an image fails, naming the module and
// why, and a render that would read one fails before its first iteration, leaving no file behind.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "e2e_support.hpp"

namespace nimbus::e2e {
namespace image_io_module_test {

namespace fs = std::filesystem;

bool contains(const std::string &text, const std::string &part) {
  return text.find(part) != std::string::npos;
}

// <prefix>/bin/nimbus (a copy, so that /proc/self/exe names the prefix) and <prefix>/lib/nimbus/plugins
// (a link to the build's); returns the copy's path.
std::string install_without_module(const fs::path &prefix) {
  fs::create_directories(prefix / "bin");
  fs::create_directories(prefix / "lib" / "nimbus");
  fs::copy_file(NIMBUS_CLI, prefix / "bin" / "nimbus");
  fs::create_directory_symlink(fs::path(NIMBUS_BINARY_DIR) / "lib" / "nimbus" / "plugins",
                               prefix / "lib" / "nimbus" / "plugins");
  return (prefix / "bin" / "nimbus").string();
}

// The box scene with the forest's environment map as its sky.
std::string scene_with_environment_map(const TestDir &dir) {
  const std::string path = dir.file("sky.yaml");
  std::ifstream box(scene("box.yaml"));
  std::ofstream(path) << box.rdbuf() << "environment: { map: " << NIMBUS_SHIPPED_SCENES
                      << "/caustics/assets/forest.exr }\n";
  return path;
}

TEST(ImageIoModule, RendersWithoutItUntilAnImageIsRead) {
  TestDir dir;
  const std::string nimbus = install_without_module(dir.path() / "prefix");
  const ProcessResult version = run_process({nimbus, "--version"}, dir.path());
  EXPECT_TRUE(exited_with(version, 0)) << version.describe();
  // The film writes its EXR and PNG with OpenEXR and libpng: no module needed.
  const ProcessResult plain =
      run_process({nimbus, "render", scene("box.yaml"), "--iterations", "1", "-q", "-o", dir.file("box.exr")},
                  dir.path());
  EXPECT_TRUE(exited_with(plain, 0)) << plain.describe();
  EXPECT_TRUE(fs::exists(dir.file("box.exr")) && fs::exists(dir.file("box.png")));

  // An environment map is read through the module: the render fails as it builds the scene, before any
  // iteration, naming the map, the module and where it was looked for.
  const ProcessResult sky = run_process(
      {nimbus, "render", scene_with_environment_map(dir), "--iterations", "1", "-o", dir.file("sky.exr")},
      dir.path());
  EXPECT_TRUE(exited_with(sky, 1)) << sky.describe();
  EXPECT_TRUE(contains(sky.err,
                       "forest.exr: cannot read environment map: cannot find the image I/O module "
                       "libnimbus_image_io.so"))
      << sky.err;
  EXPECT_TRUE(contains(sky.err, (dir.path() / "prefix" / "lib" / "nimbus" / "host").string())) << sky.err;
  EXPECT_FALSE(fs::exists(dir.file("sky.exr")));
  EXPECT_FALSE(fs::exists(dir.file("sky.exr.ckpt")));

  // Reading an EXR back (compare) needs it too.
  const ProcessResult compare =
      run_process({nimbus, "compare", dir.file("box.exr"), dir.file("box.exr")}, dir.path());
  EXPECT_TRUE(compare.exited && compare.exit_code != 0) << compare.describe();
  EXPECT_TRUE(contains(compare.err, "cannot find the image I/O module")) << compare.err;
}

TEST(ImageIoModule, DamagedModuleIsNamedWithTheLoadersReason) {
  TestDir dir;
  const std::string nimbus = install_without_module(dir.path() / "prefix");
  const fs::path module = dir.path() / "prefix" / "lib" / "nimbus" / "host" / "libnimbus_image_io.so";
  fs::create_directories(module.parent_path());
  std::ofstream(module) << std::string(256, '#');  // longer than an ELF header, so dlopen reads one

  const ProcessResult r = run_process(
      {nimbus, "render", scene_with_environment_map(dir), "--iterations", "1", "-o", dir.file("x.exr")},
      dir.path());
  EXPECT_TRUE(exited_with(r, 1)) << r.describe();
  EXPECT_TRUE(contains(r.err, "cannot load the image I/O module '" + module.string() + "'")) << r.err;
  EXPECT_TRUE(contains(r.err, "invalid ELF header")) << r.err;  // dlopen's reason
  EXPECT_FALSE(fs::exists(dir.file("x.exr")));
}

// Start-up loads no image reader: OpenImageIO (0.2 s of relocations) comes only with the module.
TEST(ImageIoModule, TheCliDoesNotLinkOpenImageIo) {
  TestDir dir;
  const ProcessResult r = run_process({"/usr/bin/readelf", "--dynamic", NIMBUS_CLI}, dir.path());
  ASSERT_TRUE(exited_with(r, 0)) << r.describe();
  EXPECT_TRUE(contains(r.out, "libOpenEXR")) << r.out;  // the film's writer: the listing is the real one
  EXPECT_FALSE(contains(r.out, "OpenImageIO")) << r.out;
}

}  // namespace image_io_module_test
}  // namespace nimbus::e2e
