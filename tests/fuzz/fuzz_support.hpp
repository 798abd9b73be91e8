// What every fuzz target shares: a scratch directory per process for the files a reader must open, and
// the check that a rejected input is answered with one clear error line.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace nimbus::fuzz {

// A directory of this process, created on first use and removed at exit.
const std::filesystem::path &scratch_dir();

// Writes `bytes` to `path`, replacing it.
void write_file(const std::filesystem::path &path, std::string_view bytes);

// `data` cut at every line equal to `separator` (the separator lines dropped), into at most `max_parts`
// parts: the last part keeps any further separators.
std::vector<std::string> split_parts(const uint8_t *data, size_t size, std::string_view separator,
                                     size_t max_parts);

// Aborts, so that libFuzzer records the input, unless `message` is one non-empty line that contains
// `path` (pass an empty path for a reason that by contract names no file).
void check_error_line(const std::string &message, const std::string &path);

// Writes `yaml` to scene.yaml in the scratch directory and reads it with parse_scene_file: the error
// message (checked by check_error_line to name scene.yaml), or nullopt when the scene loads (its warnings
// checked the same way). For the readers whose own errors hold only the reason, to which the scene adds
// its position and the path.
std::optional<std::string> scene_error(std::string_view yaml);

// Aborts with `what` on stderr unless `condition` holds.
void require(bool condition, const std::string &what);

}  // namespace nimbus::fuzz
