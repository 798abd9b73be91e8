// The CLI without its image I/O module (core/image_io.hpp): a copy of the executable in a prefix that
// has the build's plugins but no lib/nimbus/host/. Commands that touch no image still work; a render
// fails before it starts, naming the module and why, and leaves no file behind.
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

TEST(ImageIoModule, MissingModuleFailsARenderBeforeItStarts) {
  TestDir dir;
  const std::string nimbus = install_without_module(dir.path() / "prefix");
  const ProcessResult version = run_process({nimbus, "--version"}, dir.path());
  EXPECT_TRUE(exited_with(version, 0)) << version.describe();

  const ProcessResult r = run_process(
      {nimbus, "render", scene("box.yaml"), "--iterations", "1", "-o", dir.file("x.exr")}, dir.path());
  EXPECT_TRUE(exited_with(r, 1)) << r.describe();
  EXPECT_TRUE(contains(r.err, "cannot find the image I/O module libnimbus_image_io.so")) << r.err;
  EXPECT_TRUE(contains(r.err, (dir.path() / "prefix" / "lib" / "nimbus" / "host").string())) << r.err;
  EXPECT_FALSE(fs::exists(dir.file("x.exr")));
  EXPECT_FALSE(fs::exists(dir.file("x.png")));
  EXPECT_FALSE(fs::exists(dir.file("x.exr.ckpt")));
}

TEST(ImageIoModule, DamagedModuleIsNamedWithTheLoadersReason) {
  TestDir dir;
  const std::string nimbus = install_without_module(dir.path() / "prefix");
  const fs::path module = dir.path() / "prefix" / "lib" / "nimbus" / "host" / "libnimbus_image_io.so";
  fs::create_directories(module.parent_path());
  std::ofstream(module) << std::string(256, '#');  // longer than an ELF header, so dlopen reads one

  const ProcessResult r = run_process(
      {nimbus, "render", scene("box.yaml"), "--iterations", "1", "-o", dir.file("x.exr")}, dir.path());
  EXPECT_TRUE(exited_with(r, 1)) << r.describe();
  EXPECT_TRUE(contains(r.err, "cannot load the image I/O module '" + module.string() + "'")) << r.err;
  EXPECT_TRUE(contains(r.err, "invalid ELF header")) << r.err;  // dlopen's reason
  EXPECT_FALSE(fs::exists(dir.file("x.exr")));
}

}  // namespace image_io_module_test
}  // namespace nimbus::e2e
