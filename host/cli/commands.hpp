// The `nimbus` subcommands. Each returns the process exit code: 0 success, 1 failure, 2 bad usage,
// 130 interrupted by Ctrl-C (after writing complete output files).
#pragma once

#include <string>
#include <vector>

namespace nimbus::cli {

inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;
inline constexpr int kExitUsage = 2;
inline constexpr int kExitInterrupted = 130;

int render_command(const std::vector<std::string> &args);
int plugins_command(const std::vector<std::string> &args);
int lightmix_command(const std::vector<std::string> &args);
int compare_command(const std::vector<std::string> &args);
int merge_command(const std::vector<std::string> &args);

// Absolute path of the running executable (for plugin and data discovery).
std::string executable_path();

}  // namespace nimbus::cli
