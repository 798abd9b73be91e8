#include "scene/scene_parser.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include <yaml-cpp/yaml.h>

#include "scene/sections.hpp"
#include "scene/yaml_document.hpp"

namespace nimbus {

namespace {

using scene_yaml::ParseFailure;
using scene_yaml::SceneSource;
using scene_yaml::YamlMap;
using scene_yaml::YamlValue;

SceneDesc read_scene(const YAML::Node &document, const SceneSource &source) {
  SceneDesc scene;
  scene.path = source.display_name;
  // An empty file (or one with only comments) is a valid, empty scene: defaults everywhere, nothing in it.
  if (!document || document.IsNull()) return scene;
  const YamlValue root(source, document, "", document.Mark());
  if (!root.is_map())
    throw ParseFailure{scene_yaml::format_error(source.display_name, root.line(), root.column(), "scene",
                                                "expected a map of sections, got " + root.describe())};
  const YamlMap sections = root.map({"render", "camera", "materials", "objects", "lights"});

  // Materials first: objects refer to them by name wherever they appear in the file.
  if (auto v = sections.get("materials")) scene.materials = scene_yaml::read_materials(*v);
  if (auto v = sections.get("render")) scene.render = scene_yaml::read_render(*v);
  if (auto v = sections.get("camera")) scene.camera = scene_yaml::read_camera(*v);
  if (auto v = sections.get("objects")) scene.shapes = scene_yaml::read_objects(*v, scene.materials);
  if (auto v = sections.get("lights")) scene.lights = scene_yaml::read_lights(*v);
  return scene;
}

// The one place exceptions stop: ParseFailure from the readers, yaml-cpp's exceptions (syntax errors carry
// a mark), and anything unexpected (e.g. bad_alloc on a huge mesh) all become Error values.
Expected<SceneDesc> parse_text(const std::string &yaml, const SceneSource &source) {
  const std::string &file = source.display_name;
  try {
    return read_scene(scene_yaml::load_single_document(yaml, file), source);
  } catch (const ParseFailure &failure) {
    return Error{failure.message};
  } catch (const YAML::Exception &e) {
    return Error{scene_yaml::format_error(file, e.mark.is_null() ? 0 : e.mark.line + 1, e.mark.column + 1,
                                          "YAML syntax", e.msg)};
  } catch (const std::exception &e) {
    return Error{
        scene_yaml::format_error(file, 0, 0, "", std::string("cannot parse the scene: ") + e.what())};
  }
}

}  // namespace

Expected<SceneDesc> parse_scene_file(const std::string &path) {
  errno = 0;
  std::ifstream in(path, std::ios::binary);
  std::error_code ec;
  if (!in || std::filesystem::is_directory(path, ec)) {
    const std::string reason = std::filesystem::is_directory(path, ec) ? "is a directory"
                               : errno != 0                            ? std::strerror(errno)
                                                                       : "cannot open";
    return Error{scene_yaml::format_error(path, 0, 0, "", "cannot read scene file: " + reason)};
  }
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) return Error{scene_yaml::format_error(path, 0, 0, "", "cannot read scene file: read error")};
  return parse_text(text.str(), SceneSource{path, std::filesystem::path(path).parent_path()});
}

Expected<SceneDesc> parse_scene_string(const std::string &yaml, const std::string &display_name) {
  return parse_text(yaml, SceneSource{display_name, {}});
}

}  // namespace nimbus
