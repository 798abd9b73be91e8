#include "scene/scene_includes.hpp"

#include <algorithm>

#include "scene/yaml_document.hpp"

namespace nimbus::scene_yaml {

namespace {

const std::vector<std::string_view> kMainSections{"render",  "camera", "materials",   "meshes",
                                                  "objects", "lights", "environment", "include"};
const std::vector<std::string_view> kIncludedSections{"materials", "meshes", "objects", "lights", "include"};

// The top-level map of a file; yaml-cpp's syntax errors are reported in the file they occur in.
YAML::Node load_document(const std::string &text, const std::string &display_name) {
  try {
    return load_single_document(text, display_name);
  } catch (const YAML::Exception &e) {
    throw ParseFailure{format_error(display_name, e.mark.is_null() ? 0 : e.mark.line + 1, e.mark.column + 1,
                                    "YAML syntax", e.msg)};
  }
}

}  // namespace

SceneFiles::SceneFiles(const YamlValue &root) {
  if (!root.source().file.empty()) {
    std::error_code ec;
    const std::filesystem::path canonical = std::filesystem::weakly_canonical(root.source().file, ec);
    if (!ec) {
      stack_.emplace_back(canonical, root.source().display_name);
      seen_.insert(canonical);
    }
  }
  add(root, true);
}

void SceneFiles::add(const YamlValue &root, bool main) {
  const YamlMap sections = root.map();
  if (!main) {
    for (const YamlMap::Entry &e : sections.entries())
      if (std::find(kMainSections.begin(), kMainSections.end(), e.key) != kMainSections.end() &&
          std::find(kIncludedSections.begin(), kIncludedSections.end(), e.key) == kIncludedSections.end())
        e.key_value.fail("only the main scene file may set '" + e.key +
                         "'; an included file may hold: " + join_names(kIncludedSections));
  }
  sections.check_keys(main ? kMainSections : kIncludedSections);
  files_.push_back({sections, main});
  if (auto v = sections.get("include")) {
    // One file or a list of them.
    if (v->is_scalar())
      include(*v);
    else
      for (const YamlValue &entry : v->sequence()) include(entry);
  }
}

void SceneFiles::include(const YamlValue &entry) {
  const std::filesystem::path path = entry.source().resolve(entry.nonempty_string()).lexically_normal();
  const std::string shown = path.string();
  Expected<std::string> text = read_source_file(path, entry.source().log);
  if (!text) entry.fail("cannot read included file '" + shown + "': " + text.error().message);

  std::error_code ec;
  const std::filesystem::path canonical = std::filesystem::weakly_canonical(path, ec);
  const auto on_stack =
      std::find_if(stack_.begin(), stack_.end(), [&](const auto &s) { return s.first == canonical; });
  if (on_stack != stack_.end()) {
    std::string cycle;
    for (auto it = on_stack; it != stack_.end(); ++it) cycle += it->second + " -> ";
    entry.fail("include cycle: " + cycle + shown);
  }
  // Read once: a file of shared materials may be included by several others without defining them twice.
  if (seen_.count(canonical)) return;
  seen_.insert(canonical);

  sources_.push_back(SceneSource{shown, path.parent_path(), path, entry.source().log});
  const SceneSource &source = sources_.back();
  const YAML::Node document = load_document(*text, source.display_name);
  if (!document || document.IsNull()) return;  // an empty file adds nothing
  const YamlValue root(source, document, "", document.Mark());
  if (!root.is_map())
    throw ParseFailure{format_error(source.display_name, root.line(), root.column(), "scene",
                                    "expected a map of sections, got " + root.describe() +
                                        " (included from " + entry.location().text() + ")")};
  stack_.emplace_back(canonical, shown);
  add(root, false);
  stack_.pop_back();
}

}  // namespace nimbus::scene_yaml
