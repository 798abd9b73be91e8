// Joining the partial EXRs of the tasks that shared one frame (nimbus render --task K --tasks N) into the
// image one render of all their iterations makes: the exact sums of every element added in task order,
// divided by the iterations of all the parts. Parts of different frames (scene, settings, plugin or host
// versions, task count) and parts that overlap (the same task twice) are refused before anything is read
// beyond their headers; missing tasks are refused unless the merge is allowed to be incomplete.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/expected.hpp"
#include "film/film.hpp"

namespace nimbus {

struct MergedFrame {
  std::unique_ptr<Film> film;  // the sums of all parts, film->iterations() the parts' total
  // The output's metadata: the parts' own where they agree (integrator, scene, seed, ...) and the merge's
  // (iterations and seconds summed, tasks, tasks_merged, and "incomplete" naming missing tasks).
  std::vector<std::pair<std::string, std::string>> strings;
  std::vector<std::pair<std::string, double>> numbers;
  std::vector<uint32_t> missing;  // tasks of the frame with no part
};

// `allow_incomplete`: merge the parts present when some tasks have none (the output says which).
Expected<MergedFrame> merge_parts(const std::vector<std::string> &paths, bool allow_incomplete);

// The merged image as a render writes its output: the EXR at `exr_path`, its PNG preview at `png_path`.
Status write_merged(const MergedFrame &frame, const std::string &exr_path, const std::string &png_path,
                    const std::string &ocio_config);

}  // namespace nimbus
