// Shared helpers of the plugin loader tests: fixture locations, a fake host, a log capture, a scratch
// directory and the fixtures' marker logs.
#pragma once

#include <gtest/gtest.h>
#include <nimbus/host.h>
#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "loader/plugin_registry.hpp"

namespace nimbus::test {

inline std::string fixture_dir(const std::string &case_name) {
  return std::string(NIMBUS_FIXTURE_ROOT) + "/" + case_name;
}
inline std::string fixture_lib(const std::string &case_name, const std::string &name) {
  return fixture_dir(case_name) + "/libfixture_" + name + ".so";
}

// Only what the registry needs from a host: get_service answering for a fixed set of "id@rev".
class FakeHost {
 public:
  explicit FakeHost(std::set<std::string> services = {"nimbus.host.film@1", "nimbus.host.rng@1"})
      : services_(std::move(services)) {
    host_.struct_size = sizeof host_;
    host_.abi = NIMBUS_ABI_VERSION_INIT;
    host_.host_data = this;
    host_.get_service = &FakeHost::get_service;
    host_.log = nullptr;
  }
  FakeHost(const FakeHost &) = delete;
  FakeHost &operator=(const FakeHost &) = delete;
  const nimbus_host_t *get() const { return &host_; }

 private:
  static const void *get_service(const nimbus_host_t *host, const char *id, uint32_t rev) {
    const auto *self = static_cast<const FakeHost *>(host->host_data);
    static const uint32_t table = sizeof(uint32_t);  // any non-NULL pointer; the registry never calls it
    return self->services_.count(std::string(id) + "@" + std::to_string(rev)) ? &table : nullptr;
  }
  nimbus_host_t host_{};
  std::set<std::string> services_;
};

struct LogCapture {
  std::vector<std::pair<int, std::string>> lines;
  PluginRegistry::LogSink sink() {
    return [this](int level, const std::string &line) { lines.emplace_back(level, line); };
  }
  std::vector<std::string> at(int level) const {
    std::vector<std::string> out;
    for (const auto &[l, text] : lines)
      if (l == level) out.push_back(text);
    return out;
  }
  std::vector<std::string> warnings() const { return at(NIMBUS_LOG_WARNING); }
};

// A fresh directory, removed with its content afterwards.
class ScratchDir {
 public:
  ScratchDir() {
    std::string pattern = (std::filesystem::temp_directory_path() / "nimbus-plugin-test-XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) ADD_FAILURE() << "mkdtemp failed";
    path_ = pattern;
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  ScratchDir(const ScratchDir &) = delete;
  ScratchDir &operator=(const ScratchDir &) = delete;
  const std::filesystem::path &path() const { return path_; }
  std::string str() const { return path_.string(); }

 private:
  std::filesystem::path path_;
};

// Sets an environment variable for a scope and restores the previous value.
class ScopedEnv {
 public:
  ScopedEnv(const char *name, const char *value) : name_(name) {
    if (const char *old = getenv(name)) old_ = old;
    value != nullptr ? setenv(name, value, 1) : unsetenv(name);
  }
  ~ScopedEnv() { old_ ? setenv(name_.c_str(), old_->c_str(), 1) : unsetenv(name_.c_str()); }
  ScopedEnv(const ScopedEnv &) = delete;
  ScopedEnv &operator=(const ScopedEnv &) = delete;

 private:
  std::string name_;
  std::optional<std::string> old_;
};

// The calls the fixtures recorded (NIMBUS_TEST_MARKER_DIR): one "<event> <detail>" per line.
class Markers {
 public:
  Markers() : env_("NIMBUS_TEST_MARKER_DIR", dir_.str().c_str()) {}
  bool exists(const std::string &fixture) const { return std::filesystem::exists(file(fixture)); }
  std::vector<std::string> events(const std::string &fixture) const {
    std::vector<std::string> out;
    std::ifstream in(file(fixture));
    for (std::string line; std::getline(in, line);) out.push_back(line);
    return out;
  }
  // Events without their details, filtered to the lifecycle calls (count/descriptor may repeat).
  std::vector<std::string> lifecycle(const std::string &fixture) const {
    std::vector<std::string> out;
    for (const auto &e : events(fixture)) {
      const std::string head = e.substr(0, e.find(' '));
      if (head != "count" && head != "descriptor") out.push_back(head);
    }
    return out;
  }

 private:
  std::filesystem::path file(const std::string &fixture) const { return dir_.path() / (fixture + ".log"); }
  ScratchDir dir_;
  ScopedEnv env_;
};

}  // namespace nimbus::test
