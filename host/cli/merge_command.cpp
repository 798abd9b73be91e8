// `nimbus merge PARTS... -o OUT.exr`: the partial EXRs of the tasks that shared a frame (nimbus render --task
// K --tasks N) joined into the image one render of all their iterations makes (render/frame_merge.hpp).
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "film/film.hpp"
#include "render/frame_merge.hpp"

namespace nimbus::cli {
namespace {

constexpr const char *kHelp =
    "usage: nimbus merge PART.exr... -o OUT.exr [--allow-incomplete]\n"
    "\n"
    "Joins the partial EXRs that `nimbus render --task K --tasks N` wrote for one frame into the image a\n"
    "single render of all their iterations makes: every element's exact sums (LightMix layers and the\n"
    "caustics element included) added and divided by the parts' total iterations. Writes OUT.exr, with\n"
    "the iterations and render seconds of all parts and the tasks merged in its metadata, and the PNG\n"
    "preview beside it.\n"
    "\n"
    "Refuses, naming the two files, parts of different frames (scene or any file it reads, settings,\n"
    "seed, plugin or Nimbus versions, task count) and parts that overlap (the same task twice).\n"
    "\n"
    "options:\n"
    "  -o, --output OUT.exr   the merged image\n"
    "  --allow-incomplete     when some tasks have no part, merge those present (the output's\n"
    "                         nimbus:incomplete names the missing tasks) instead of failing\n"
    "\n"
    "example: nimbus merge out/parts/shot.part*of4.exr -o out/shot.exr\n";

struct Args {
  std::vector<std::string> parts;
  std::string output;
  bool allow_incomplete = false;
};

// Returns an error message, or an empty string on success.
std::string parse_args(const std::vector<std::string> &args, Args &a, bool &help) {
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string &k = args[i];
    if (k == "--help" || k == "-h") {
      help = true;
      return "";
    } else if (k == "-o" || k == "--output") {
      if (i + 1 >= args.size() || args[i + 1].empty()) return k + ": expected a file name";
      a.output = args[++i];
    } else if (k == "--allow-incomplete") {
      a.allow_incomplete = true;
    } else if (!k.empty() && k[0] == '-') {
      return "unknown option '" + k + "'";
    } else {
      a.parts.push_back(k);
    }
  }
  if (a.parts.empty()) return "no parts given";
  if (a.output.empty()) return "no output given (-o OUT.exr)";
  if (std::filesystem::path(a.output).extension() == ".png")
    return "-o: the output is an EXR; its PNG preview is written beside it";
  return "";
}

}  // namespace

int merge_command(const std::vector<std::string> &argv) {
  Args a;
  bool help = false;
  if (const std::string err = parse_args(argv, a, help); !err.empty()) {
    std::fprintf(stderr, "nimbus merge: %s\n\n%s", err.c_str(), kHelp);
    return kExitUsage;
  }
  if (help) {
    std::fputs(kHelp, stdout);
    return kExitOk;
  }
  auto merged = merge_parts(a.parts, a.allow_incomplete);
  if (!merged) {
    std::fprintf(stderr, "nimbus merge: %s\n", merged.error().message.c_str());
    return kExitFailure;
  }
  const MergedFrame &frame = merged.value();
  std::error_code ec;
  if (const auto parent = std::filesystem::path(a.output).parent_path(); !parent.empty())
    std::filesystem::create_directories(parent, ec);
  const std::string png = std::filesystem::path(a.output).replace_extension(".png").string();
  if (Status s = write_merged(frame, a.output, png, default_ocio_config_path()); !s) {
    std::fprintf(stderr, "nimbus merge: %s\n", s.error().message.c_str());
    return kExitFailure;
  }
  std::fprintf(stderr, "nimbus merge: %zu parts, %llu iterations -> %s, %s%s\n", a.parts.size(),
               (unsigned long long)frame.film->iterations(), a.output.c_str(), png.c_str(),
               frame.missing.empty() ? "" : " (incomplete: tasks missing, see nimbus:incomplete)");
  return kExitOk;
}

}  // namespace nimbus::cli
