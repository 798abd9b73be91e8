// The files of one scene: the main file and every file it includes (`include: [a.yaml, ...]`), each
// parsed once. Included files hold the sections that can be appended to — materials, meshes, objects,
// lights — and may include further files; the main file alone sets render, camera and environment.
#pragma once

#include <deque>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "core/expected.hpp"
#include "scene/yaml_value.hpp"

namespace nimbus::scene_yaml {

struct SceneFile {
  YamlMap sections;
  bool main = false;
};

class SceneFiles {
 public:
  // Reads the includes of `root` (the main file's top-level map) recursively. Throws ParseFailure on a
  // missing or malformed included file, an include cycle, or a section an included file may not hold.
  explicit SceneFiles(const YamlValue &root);
  SceneFiles(const SceneFiles &) = delete;
  SceneFiles &operator=(const SceneFiles &) = delete;

  // Depth first in the order written: each file comes before the files it includes, so that the items of
  // an included file are appended after those of the file that includes it.
  const std::vector<SceneFile> &files() const { return files_; }
  const SceneFile &main() const { return files_.front(); }

 private:
  void add(const YamlValue &root, bool main);
  void include(const YamlValue &entry);

  std::deque<SceneSource> sources_;  // stable addresses: every YamlValue of an included file points here
  std::vector<SceneFile> files_;
  // Canonical paths of the files being read (for cycles) with the name each was reached by, and of all
  // all files read so far (a file included twice is read once).
  std::vector<std::pair<std::filesystem::path, std::string>> stack_;
  std::set<std::filesystem::path> seen_;
};

}  // namespace nimbus::scene_yaml
