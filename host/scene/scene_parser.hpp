// YAML scene files → SceneDesc. The format is documented in docs/scene-format.md.
//
// Every failure is an Error whose message is one line:
//   FILE:LINE:COLUMN: error: KEY.PATH: MESSAGE      e.g.  scenes/x.yaml:12:7: error: objects[2].radius: must
//   be > 0 (got -1)
// (line and column 1-based). Problems without a position, such as an unreadable scene file, read
// "FILE: error: MESSAGE". Nothing throws out of these functions and nothing aborts on bad input.
#pragma once

#include <string>

#include "core/expected.hpp"
#include "scene/scene_desc.hpp"

namespace nimbus {

// Reads and parses a scene file. Relative paths inside it (mesh files) resolve against its directory;
// errors and SceneDesc::path name the file as given.
Expected<SceneDesc> parse_scene_file(const std::string &path);

// Parses scene text; `display_name` stands for the file in error messages and SceneDesc::path. Relative
// paths inside resolve against the current directory.
Expected<SceneDesc> parse_scene_string(const std::string &yaml, const std::string &display_name);

}  // namespace nimbus
