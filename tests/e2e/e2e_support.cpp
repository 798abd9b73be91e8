#include "e2e_support.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <iterator>
#include <sstream>

namespace nimbus::e2e {

std::string scene(const std::string &name) { return std::string(NIMBUS_E2E_SCENES) + "/" + name; }

TestDir::TestDir() {
  const auto *info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::string name = info ? std::string(info->test_suite_name()) + "." + info->name() : "unnamed";
  root_ = std::filesystem::temp_directory_path() / ("nimbus-e2e-" + std::to_string(::getpid()));
  path_ = root_ / name;
  std::filesystem::remove_all(path_);
  std::filesystem::create_directories(path_);
}

TestDir::~TestDir() {
  if (::testing::Test::HasFailure()) {
    std::fprintf(stderr, "[  KEPT    ] %s\n", path_.c_str());
    return;
  }
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
  // Each directory up to root_ goes once it is empty (a parameterised test's name holds a '/').
  for (auto dir = path_.parent_path(); dir.string().size() >= root_.string().size(); dir = dir.parent_path())
    if (!std::filesystem::remove(dir, ec)) break;
}

std::vector<std::string> TestDir::entries() const {
  std::vector<std::string> names;
  for (const auto &e : std::filesystem::directory_iterator(path_))
    names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

std::vector<std::string> TestDir::temporaries() const {
  std::vector<std::string> out;
  for (const std::string &n : entries())
    if (n.find(".tmp-") != std::string::npos) out.push_back(n);
  return out;
}

std::vector<std::string> nimbus_argv(const std::vector<std::string> &args) {
  std::vector<std::string> argv{NIMBUS_CLI};
  argv.insert(argv.end(), args.begin(), args.end());
  return argv;
}

ProcessResult run_nimbus(const std::vector<std::string> &args, const TestDir &dir) {
  return run_process(nimbus_argv(args), dir.path());
}

bool exited_with(const ProcessResult &r, int code) { return r.exited && !r.timed_out && r.exit_code == code; }

std::optional<ImageLayers> read_exr(const std::string &path) {
  auto img = read_exr_layers(path);
  if (!img) {
    ADD_FAILURE() << "cannot read " << path << ": " << img.error().message;
    return std::nullopt;
  }
  return std::move(img.value());
}

const std::vector<float> &plane(const ImageLayers &img, const std::string &name) {
  static const std::vector<float> kEmpty;
  const auto it = img.channels.find(name);
  if (it == img.channels.end()) {
    ADD_FAILURE() << "the EXR has no channel " << name;
    return kEmpty;
  }
  return it->second;
}

std::optional<std::string> meta_string(const ImageLayers &img, const std::string &key) {
  const auto it = img.strings.find(key);
  return it == img.strings.end() ? std::nullopt : std::optional(it->second);
}

std::optional<double> meta_number(const ImageLayers &img, const std::string &key) {
  const auto it = img.numbers.find(key);
  return it == img.numbers.end() ? std::nullopt : std::optional(it->second);
}

std::optional<uint64_t> recorded_seed(const ImageLayers &img) {
  if (const auto s = meta_string(img, "nimbus:seed")) {
    uint64_t v = 0;
    const auto [end, ec] = std::from_chars(s->data(), s->data() + s->size(), v);
    if (ec != std::errc() || end != s->data() + s->size()) return std::nullopt;
    return v;
  }
  if (const auto n = meta_number(img, "nimbus:seed"); n && *n >= 0 && *n == std::trunc(*n))
    return uint64_t(*n);
  return std::nullopt;
}

std::string read_bytes(const std::string &path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

void write_bytes(const std::string &path, const std::string &bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

}  // namespace nimbus::e2e
