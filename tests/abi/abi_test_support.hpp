// Helpers of the frozen-1.0 fixture tests: running the CLI with an environment, a scratch directory,
// and comparing rendered layers with the stored reference.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "film/image_read.hpp"

namespace nimbus::abi_test {

// Where the build put the fixtures, and the scene and reference they are tested with.
inline std::string fixture_dir() { return NIMBUS_ABI_FIXTURE_DIR; }
inline std::string scene_path() { return std::string(NIMBUS_SOURCE_DIR) + "/tests/scenes/abi-cornell.yaml"; }
inline std::string reference_path() {
  return std::string(NIMBUS_SOURCE_DIR) + "/tests/abi/abi-cornell-ref.exr";
}

struct RunResult {
  int exit_code = -1;  // -1 when the process did not exit normally
  std::string out, err;
};

// Runs `argv` (argv[0] a path) with NIMBUS_PLUGIN_PATH set to `plugin_path`, output captured in `dir`.
RunResult run_with_plugin_path(const std::vector<std::string> &argv, const std::string &plugin_path,
                               const std::filesystem::path &dir);

// A fresh directory per test, removed afterwards unless the test failed.
class ScratchDir {
 public:
  ScratchDir();
  ~ScratchDir();
  ScratchDir(const ScratchDir &) = delete;
  ScratchDir &operator=(const ScratchDir &) = delete;
  const std::filesystem::path &path() const { return path_; }
  std::string file(const std::string &name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

// Fails the test unless layer `name` exists with 3 channels and only finite values.
void expect_finite_layer(const ImageLayers &img, const std::string &name);
double layer_mean(const ImageLayers &img, const std::string &name);
// sqrt(sum (a - ref)^2 / sum ref^2) over the layer's channels; infinity if the layers do not match in shape.
double relative_rmse(const ImageLayers &img, const ImageLayers &ref, const std::string &name);

// Relative RMSE allowed against the reference: same seed, same host, same image up to float noise.
constexpr double kReferenceTolerance = 1e-5;

// NIMBUS_ABI_UPDATE_REFERENCE=1 makes the reference test write the reference instead of comparing.
bool updating_reference();

}  // namespace nimbus::abi_test
