#include "abi_test_support.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>

extern char **environ;

namespace nimbus::abi_test {
namespace {

std::string slurp(const std::filesystem::path &p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

}  // namespace

RunResult run_with_plugin_path(const std::vector<std::string> &argv, const std::string &plugin_path,
                               const std::filesystem::path &dir) {
  // The child's environment: ours without NIMBUS_PLUGIN_PATH, plus the one under test.
  std::vector<std::string> env_storage = {"NIMBUS_PLUGIN_PATH=" + plugin_path};
  for (char **e = environ; *e; ++e)
    if (std::strncmp(*e, "NIMBUS_PLUGIN_PATH=", 19) != 0) env_storage.emplace_back(*e);
  std::vector<char *> envp, args;
  for (auto &s : env_storage) envp.push_back(s.data());
  envp.push_back(nullptr);
  std::vector<std::string> argv_storage = argv;
  for (auto &s : argv_storage) args.push_back(s.data());
  args.push_back(nullptr);

  // Output to files, not pipes: nothing to pump, no deadlock however much the child prints.
  const std::string out_path = (dir / "stdout.txt").string(), err_path = (dir / "stderr.txt").string();
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, 2, err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, args[0], &actions, nullptr, args.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  RunResult r;
  if (rc != 0) {
    r.err = std::string("cannot start ") + args[0] + ": " + std::strerror(rc);
    return r;
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
  r.out = slurp(out_path);
  r.err = slurp(err_path);
  return r;
}

ScratchDir::ScratchDir() {
  const auto *info = ::testing::UnitTest::GetInstance()->current_test_info();
  path_ = std::filesystem::path(NIMBUS_BINARY_DIR) / "tests" / "abi_scratch" /
          (std::string(info->test_suite_name()) + "." + info->name());
  std::filesystem::remove_all(path_);
  std::filesystem::create_directories(path_);
}

ScratchDir::~ScratchDir() {
  if (::testing::Test::HasFailure())
    std::fprintf(stderr, "test files kept in %s\n", path_.c_str());
  else
    std::filesystem::remove_all(path_);
}

void expect_finite_layer(const ImageLayers &img, const std::string &name) {
  const auto it = img.layers.find(name);
  ASSERT_NE(it, img.layers.end()) << "no layer '" << name << "'";
  EXPECT_EQ(it->second.channel_names.size(), 3u) << name;
  ASSERT_EQ(it->second.data.size(), size_t(img.width) * img.height * it->second.channel_names.size()) << name;
  size_t bad = 0;
  for (float v : it->second.data) bad += !std::isfinite(v);
  EXPECT_EQ(bad, 0u) << "non-finite values in layer '" << name << "'";
}

double layer_mean(const ImageLayers &img, const std::string &name) {
  const auto it = img.layers.find(name);
  if (it == img.layers.end() || it->second.data.empty()) return 0;
  double sum = 0;
  for (float v : it->second.data) sum += v;
  return sum / double(it->second.data.size());
}

double relative_rmse(const ImageLayers &img, const ImageLayers &ref, const std::string &name) {
  const auto a = img.layers.find(name), b = ref.layers.find(name);
  if (a == img.layers.end() || b == ref.layers.end() || a->second.data.size() != b->second.data.size() ||
      img.width != ref.width || img.height != ref.height)
    return std::numeric_limits<double>::infinity();
  double err = 0, norm = 0;
  for (size_t i = 0; i < a->second.data.size(); ++i) {
    const double d = double(a->second.data[i]) - b->second.data[i];
    err += d * d;
    norm += double(b->second.data[i]) * b->second.data[i];
  }
  return norm > 0 ? std::sqrt(err / norm) : std::sqrt(err);
}

bool updating_reference() {
  const char *v = std::getenv("NIMBUS_ABI_UPDATE_REFERENCE");
  return v && std::strcmp(v, "1") == 0;
}

}  // namespace nimbus::abi_test
