// The files a scene is made from. Every file the parser reads (the scene file, included files, OBJ and
// glTF meshes with the .mtl files, buffers and images their loaders pull in, subdivision cages) is read
// through one SourceLog, which keeps its path and a hash of its bytes: SceneDesc::sources, what a
// checkpoint's fingerprint is made of, so that editing any of them is noticed. Textures and environment maps
// are opened when the world is built, not by the parser, and are not in it.
#pragma once

#include <cstdint>
#include <filesystem>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "core/expected.hpp"

namespace nimbus {

struct SourceFile {
  // Relative to the scene file's directory where the file lies below it, else absolute: the same
  // whichever directory the renderer runs in. The scene itself is first, under the name it was given.
  std::string path;
  std::string hash;  // core/checksum.hpp content_hash of the bytes
  uint64_t bytes = 0;
};

class SourceLog {
 public:
  // `scene_dir`: the scene file's directory (empty: the current directory).
  explicit SourceLog(const std::filesystem::path &scene_dir);

  // Records bytes that were read, once per file (a file read again is not recorded twice).
  void record(const std::filesystem::path &path, std::string_view bytes);
  // The scene's own text, first, under `name` (which need not be a file).
  void record_scene(const std::string &name, std::string_view bytes);

  std::vector<SourceFile> take() { return std::move(files_); }

 private:
  std::filesystem::path base_;
  std::set<std::filesystem::path> seen_;
  std::vector<SourceFile> files_;
};

// The bytes of a file, or the reason it cannot be read ("No such file or directory", "is a directory");
// recorded in `log` when it is not null.
Expected<std::string> read_source_file(const std::filesystem::path &path, SourceLog *log);

}  // namespace nimbus
