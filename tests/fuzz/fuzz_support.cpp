#include "fuzz_support.hpp"

#include <cstdio>
#include <cstdlib>
#include <fstream>

#include "../film/scratch_dir.hpp"
#include "scene/scene_parser.hpp"

namespace nimbus::fuzz {

const std::filesystem::path &scratch_dir() {
  static const test::ScratchDir dir;
  return dir.path();
}

void write_file(const std::filesystem::path &path, std::string_view bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), std::streamsize(bytes.size()));
  require(bool(out), "cannot write the fuzz input file " + path.string());
}

std::vector<std::string> split_parts(const uint8_t *data, size_t size, std::string_view separator,
                                     size_t max_parts) {
  const std::string_view text(reinterpret_cast<const char *>(data), size);
  std::vector<std::string> parts;
  size_t start = 0, line = 0;
  while (parts.size() + 1 < max_parts && line < text.size()) {
    const size_t end = std::min(text.find('\n', line), text.size());
    if (text.substr(line, end - line) == separator) {
      parts.emplace_back(text.substr(start, line - start));
      start = std::min(end + 1, text.size());
    }
    line = end + 1;
  }
  parts.emplace_back(text.substr(start));
  return parts;
}

void require(bool condition, const std::string &what) {
  if (condition) return;
  std::fprintf(stderr, "fuzz check failed: %s\n", what.c_str());
  std::abort();
}

void check_error_line(const std::string &message, const std::string &path) {
  require(!message.empty(), "an input was rejected with an empty message");
  require(message.find('\n') == std::string::npos, "the error spans several lines: \"" + message + "\"");
  require(message.find(path) != std::string::npos,
          "the error does not name " + path + ": \"" + message + "\"");
}

std::optional<std::string> scene_error(std::string_view yaml) {
  const std::string path = (scratch_dir() / "scene.yaml").string();
  write_file(path, yaml);
  const Expected<SceneDesc> scene = parse_scene_file(path);
  if (scene) {
    for (const std::string &warning : scene->warnings) check_error_line(warning, path);
    return std::nullopt;
  }
  check_error_line(scene.error().message, path);
  return scene.error().message;
}

}  // namespace nimbus::fuzz
