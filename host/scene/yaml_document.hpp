// Loading the one YAML document of a scene file, working around yaml-cpp 0.7 (Debian 12) pitfalls.
#pragma once

#include <string>

#include <yaml-cpp/yaml.h>

namespace nimbus::scene_yaml {

// The document in `text` as a node tree (a null node for an empty file). Throws ParseFailure when the
// text holds a second document or a stray token yaml-cpp would otherwise skip, and yaml-cpp's
// ParserException (with a mark) for syntax errors.
YAML::Node load_single_document(const std::string &text, const std::string &display_name);

}  // namespace nimbus::scene_yaml
