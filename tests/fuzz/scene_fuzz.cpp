// The YAML scene reader with includes (scene/scene_parser.hpp, scene/scene_includes.hpp). The input is up
// to three files cut at lines "#--8<--": main.yaml, a.yaml and b.yaml in the scratch directory, so the
// main file may include the others, they may include each other or themselves (a cycle must be an
// error, not a hang), and any file may name a missing one. The scene is read with parse_scene_file; a
// rejection must be one line "FILE[:LINE:COLUMN]: error: ..." naming the file at fault: one of the
// three, or another existing file the scene included.
#include <cstdint>
#include <regex>
#include <string>

#include "fuzz_support.hpp"
#include "scene/scene_parser.hpp"

namespace {

// The file an error line names: what precedes ": error: ", without ":LINE:COLUMN".
std::string file_named(const std::string &message) {
  const size_t end = message.find(": error: ");
  nimbus::fuzz::require(end != std::string::npos, "the error has no ': error: ': \"" + message + "\"");
  static const std::regex position(":[0-9]+:[0-9]+$");
  return std::regex_replace(message.substr(0, end), position, "");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  using namespace nimbus::fuzz;
  const std::filesystem::path &dir = scratch_dir();
  const std::vector<std::string> parts = split_parts(data, size, "#--8<--", 3);
  const char *const names[] = {"main.yaml", "a.yaml", "b.yaml"};
  for (size_t i = 0; i < 3; ++i) {
    std::error_code ec;
    if (i < parts.size())
      write_file(dir / names[i], parts[i]);
    else
      std::filesystem::remove(dir / names[i], ec);  // a file the input does not give is missing
  }
  const std::string main = (dir / "main.yaml").string();
  const nimbus::Expected<nimbus::SceneDesc> scene = nimbus::parse_scene_file(main);
  if (scene) return 0;
  const std::string &message = scene.error().message;
  check_error_line(message, "");
  const std::string file = file_named(message);
  require(file == main || std::filesystem::is_regular_file(file),
          "the error names '" + file + "', which is neither the scene nor a file it includes: \"" + message +
              "\"");
  return 0;
}
