#include "scene/scene_parser.hpp"

#include <iterator>
#include <string>

#include <yaml-cpp/yaml.h>

#include "scene/scene_includes.hpp"
#include "scene/sections.hpp"
#include "scene/yaml_document.hpp"

namespace nimbus {

namespace {

using scene_yaml::ParseFailure;
using scene_yaml::SceneSource;
using scene_yaml::YamlMap;
using scene_yaml::YamlValue;

// Materials of every file share one namespace, so that objects anywhere can name them.
void append_materials(const YamlValue &section, std::vector<MaterialDesc> &materials) {
  for (MaterialDesc &m : scene_yaml::read_materials(section)) {
    for (const MaterialDesc &other : materials)
      if (other.name == m.name)
        throw ParseFailure{scene_yaml::format_error(
            m.where.file, m.where.line, m.where.column, "materials." + scene_yaml::abbreviate(m.name),
            "material '" + scene_yaml::abbreviate(m.name) + "' is already defined at " + other.where.text())};
    materials.push_back(std::move(m));
  }
}

template <class T>
void append(std::vector<T> &to, std::vector<T> &&from) {
  to.insert(to.end(), std::make_move_iterator(from.begin()), std::make_move_iterator(from.end()));
}

SceneDesc read_scene(const YAML::Node &document, const SceneSource &source) {
  SceneDesc scene;
  scene.path = source.display_name;
  // An empty file (or one with only comments) is a valid, empty scene: defaults everywhere, nothing in it.
  if (!document || document.IsNull()) return scene;
  const YamlValue root(source, document, "", document.Mark());
  if (!root.is_map())
    throw ParseFailure{scene_yaml::format_error(source.display_name, root.line(), root.column(), "scene",
                                                "expected a map of sections, got " + root.describe())};
  const scene_yaml::SceneFiles files(root);
  const YamlMap &main = files.main().sections;
  const auto each = [&](std::string_view section, const auto &read) {
    for (const scene_yaml::SceneFile &file : files.files())
      if (auto v = file.sections.get(section)) read(*v);
  };

  // Materials and named meshes first: objects refer to them by name wherever they appear. Render and
  // camera before objects too: `level: auto` of subdivision surfaces depends on them. Lights before the
  // environment: a sky takes its sun from the sun light.
  each("materials", [&](const YamlValue &v) { append_materials(v, scene.materials); });
  if (auto v = main.get("render")) scene.render = scene_yaml::read_render(*v);
  if (auto v = main.get("camera")) scene.camera = scene_yaml::read_camera(*v);
  scene_yaml::MeshLibrary meshes;
  each("meshes", [&](const YamlValue &v) { scene_yaml::read_meshes(v, meshes); });
  each("lights",
       [&](const YamlValue &v) { append(scene.lights, scene_yaml::read_lights(v, scene.camera.shutter)); });
  if (auto v = main.get("environment")) scene.environment = scene_yaml::read_environment(*v, scene.lights);
  scene_yaml::ObjectContext objects{
      scene.materials, meshes, scene.camera, scene.render, scene.warnings, {}, {}};
  each("objects", [&](const YamlValue &v) { append(scene.shapes, scene_yaml::read_objects(v, objects)); });
  return scene;
}

// The one place exceptions stop (and where the files read are handed to the SceneDesc): ParseFailure from the
// readers, yaml-cpp's exceptions (syntax errors carry a mark), and anything unexpected (e.g. bad_alloc on a
// huge mesh) all become Error values.
Expected<SceneDesc> parse_text(const std::string &yaml, const SceneSource &source, SourceLog &log) {
  const std::string &file = source.display_name;
  try {
    SceneDesc scene = read_scene(scene_yaml::load_single_document(yaml, file), source);
    scene.sources = log.take();
    return scene;
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
  const std::filesystem::path dir = std::filesystem::path(path).parent_path();
  SourceLog log(dir);
  Expected<std::string> text = read_source_file(path, &log);
  if (!text)
    return Error{scene_yaml::format_error(path, 0, 0, "", "cannot read scene file: " + text.error().message)};
  return parse_text(*text, SceneSource{path, dir, path, &log}, log);
}

Expected<SceneDesc> parse_scene_string(const std::string &yaml, const std::string &display_name) {
  SourceLog log({});
  log.record_scene(display_name, yaml);
  return parse_text(yaml, SceneSource{display_name, {}, {}, &log}, log);
}

}  // namespace nimbus
