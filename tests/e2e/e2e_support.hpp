// Shared pieces of the end-to-end tests: a scratch directory per test, the CLI and fixture paths, and
// reading the CLI's output files back.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "film/image_read.hpp"
#include "subprocess.hpp"

namespace nimbus::e2e {

// Absolute path of a scene under tests/e2e/scenes.
std::string scene(const std::string &name);

// A fresh directory for the running test, named after it; removed afterwards unless the test failed
// (then its path is printed so the files can be inspected).
class TestDir {
 public:
  TestDir();
  ~TestDir();
  TestDir(const TestDir &) = delete;
  TestDir &operator=(const TestDir &) = delete;

  const std::filesystem::path &path() const { return path_; }
  std::string file(const std::string &name) const { return (path_ / name).string(); }
  // Names of the entries directly inside, sorted.
  std::vector<std::string> entries() const;
  // Entries that look like abandoned atomic-write temporaries ("<name>.tmp-<pid>").
  std::vector<std::string> temporaries() const;

 private:
  std::filesystem::path root_;  // this process's directory; a parameterised test's name nests below it
  std::filesystem::path path_;
};

// Runs `nimbus ARGS...` in `dir` and waits for it.
ProcessResult run_nimbus(const std::vector<std::string> &args, const TestDir &dir);
// The argv of `nimbus ARGS...`, for starting the CLI with Process and not waiting.
std::vector<std::string> nimbus_argv(const std::vector<std::string> &args);

bool exited_with(const ProcessResult &r, int code);

// The EXR read back, or nullopt after recording a test failure that says why.
std::optional<ImageLayers> read_exr(const std::string &path);

// Plane `name` ("R", "G", "B") of `img`; records a failure and returns an empty plane when missing.
const std::vector<float> &plane(const ImageLayers &img, const std::string &name);

// A header attribute, or nullopt when absent.
std::optional<std::string> meta_string(const ImageLayers &img, const std::string &key);
std::optional<double> meta_number(const ImageLayers &img, const std::string &key);
// nimbus:seed, written as a decimal string (exact for any 64-bit seed) or, by older writers, a number.
std::optional<uint64_t> recorded_seed(const ImageLayers &img);

std::string read_bytes(const std::string &path);
void write_bytes(const std::string &path, const std::string &bytes);

}  // namespace nimbus::e2e
