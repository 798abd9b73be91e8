// A task's share of a frame (nimbus render --task K --tasks N) as a two-part EXR that `nimbus merge` adds up.
// Part 0 is what a normal render writes (the task's own image, viewable in any EXR viewer, with its
// metadata); part 1, "nimbus_sums", holds every element's running double sums bit for bit, each as two
// UINT channels "<channel>.lo" and "<channel>.hi" (EXR has no 64-bit float): so the merged sums are
// those of one render up to the order of the additions.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "core/expected.hpp"
#include "film/film.hpp"

namespace nimbus {

inline constexpr const char *kSumsPartName = "nimbus_sums";

struct PartialElement {
  std::string name;  // "beauty" for beauty, else the film's element name ("caustics", "lightmix.key")
  uint32_t channels = 0;
  std::vector<double> sums;  // width * height * channels, channel-interleaved
};

struct PartialImage {
  uint32_t width = 0, height = 0;
  std::vector<PartialElement> elements;  // beauty first, then the film's order
  // Part 0's "nimbus:<key>" attributes, without the prefix.
  std::map<std::string, std::string> strings;
  std::map<std::string, double> numbers;
};

// Part 0 as Film::write_exr writes it (same metadata keys and types), then the sums; atomically.
Status write_partial_exr(const Film &film, const std::string &path,
                         const std::vector<std::pair<std::string, std::string>> &string_meta,
                         const std::vector<std::pair<std::string, double>> &numeric_meta);

// The sums and metadata of a partial EXR. Errors name the path and the reason (not an EXR, no sums part,
// channels that do not pair up, a part cut short).
Expected<PartialImage> read_partial_exr(const std::string &path);

}  // namespace nimbus
