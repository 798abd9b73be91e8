// Search directory order and deduplication, on directory trees made in a scratch directory.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "plugin_test_support.hpp"

namespace nimbus {
namespace plugin_search_paths_test {
namespace fs = std::filesystem;
using test::ScratchDir;

// The compile-time install location, listed last when it exists on this machine.
std::vector<std::string> without_install_dir(std::vector<std::string> dirs) {
  std::error_code ec;
  const fs::path installed = fs::path(NIMBUS_INSTALL_PREFIX) / NIMBUS_INSTALL_PLUGIN_DIR;
  if (!dirs.empty() && fs::equivalent(dirs.back(), installed, ec)) dirs.pop_back();
  return dirs;
}

void touch(const fs::path &p) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << "#!/bin/sh\n";
}

TEST(PluginSearchPaths, EnvironmentEntriesInOrderSkippingEmptyOnes) {
  ScratchDir tmp;
  fs::create_directories(tmp.path() / "a");
  fs::create_directories(tmp.path() / "b");
  const std::string a = (tmp.path() / "a").string(), b = (tmp.path() / "b").string();
  const std::string missing = (tmp.path() / "missing").string();
  const std::string env = ":" + b + "::" + a + "/:" + missing + ":";
  EXPECT_EQ(without_install_dir(PluginRegistry::search_paths(env.c_str(), "")),
            (std::vector<std::string>{b, a, missing}));
}

TEST(PluginSearchPaths, DeduplicatesByCanonicalPath) {
  ScratchDir tmp;
  fs::create_directories(tmp.path() / "real");
  fs::create_directory_symlink(tmp.path() / "real", tmp.path() / "link");
  const std::string real = (tmp.path() / "real").string();
  const std::string env = real + ":" + (tmp.path() / "link").string() + ":" + real + "/../real";
  EXPECT_EQ(without_install_dir(PluginRegistry::search_paths(env.c_str(), "")),
            (std::vector<std::string>{real}));
}

TEST(PluginSearchPaths, BuildTreeOrPrefixOfTheExecutable) {
  ScratchDir tmp;
  const fs::path build = tmp.path() / "build";
  touch(build / "bin" / "nimbus");
  fs::create_directories(build / "lib" / "nimbus" / "plugins");
  fs::create_directories(tmp.path() / "user");
  const std::string user = (tmp.path() / "user").string();
  EXPECT_EQ(
      without_install_dir(PluginRegistry::search_paths(user.c_str(), (build / "bin" / "nimbus").string())),
      (std::vector<std::string>{user, (build / "lib" / "nimbus" / "plugins").string()}));
}

TEST(PluginSearchPaths, ExecutableSymlinkResolvesToItsRealPrefix) {
  ScratchDir tmp;
  const fs::path prefix = tmp.path() / "opt";
  touch(prefix / "bin" / "nimbus");
  fs::create_directories(prefix / "lib" / "nimbus" / "plugins");
  fs::create_directories(tmp.path() / "usr" / "bin");
  fs::create_symlink(prefix / "bin" / "nimbus", tmp.path() / "usr" / "bin" / "nimbus");
  EXPECT_EQ(
      without_install_dir(PluginRegistry::search_paths(nullptr, (tmp.path() / "usr/bin/nimbus").string())),
      (std::vector<std::string>{(prefix / "lib" / "nimbus" / "plugins").string()}));
}

TEST(PluginSearchPaths, ExecutableDirectoriesAreListedOnlyWhenTheyExist) {
  ScratchDir tmp;
  touch(tmp.path() / "bin" / "nimbus");
  EXPECT_TRUE(without_install_dir(PluginRegistry::search_paths(nullptr, (tmp.path() / "bin/nimbus").string()))
                  .empty());
}

TEST(PluginSearchPaths, DefaultReadsTheEnvironment) {
  ScratchDir tmp;
  test::ScopedEnv env("NIMBUS_PLUGIN_PATH", tmp.str().c_str());
  const auto dirs = PluginRegistry::default_search_paths("");
  ASSERT_FALSE(dirs.empty());
  EXPECT_EQ(dirs.front(), tmp.str());
}

TEST(PluginSearchPaths, InstallDirectoryIsLastWhenPresent) {
  const fs::path installed = fs::path(NIMBUS_INSTALL_PREFIX) / NIMBUS_INSTALL_PLUGIN_DIR;
  const auto dirs = PluginRegistry::search_paths(nullptr, "");
  if (fs::is_directory(installed)) {
    ASSERT_EQ(dirs.size(), 1u);
    EXPECT_TRUE(fs::equivalent(dirs[0], installed));
  } else {
    EXPECT_TRUE(dirs.empty());
  }
}

}  // namespace plugin_search_paths_test
}  // namespace nimbus
