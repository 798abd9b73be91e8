#include "scene/yaml_document.hpp"

#include <sstream>
#include <vector>

#include <yaml-cpp/eventhandler.h>

#include "scene/yaml_value.hpp"

namespace nimbus::scene_yaml {

namespace {

// Records where each document starts; builds nothing.
class DocumentStarts final : public YAML::EventHandler {
 public:
  std::vector<YAML::Mark> starts;

  void OnDocumentStart(const YAML::Mark &mark) override { starts.push_back(mark); }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark &, YAML::anchor_t) override {}
  void OnAlias(const YAML::Mark &, YAML::anchor_t) override {}
  void OnScalar(const YAML::Mark &, const std::string &, YAML::anchor_t, const std::string &) override {}
  void OnSequenceStart(const YAML::Mark &, const std::string &, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {}
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark &, const std::string &, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {}
  void OnMapEnd() override {}
};

}  // namespace

YAML::Node load_single_document(const std::string &text, const std::string &display_name) {
  // First pass over the whole stream, stopping at the second document. Not YAML::LoadAll: on a token that
  // cannot start a node (e.g. a stray ',') yaml-cpp 0.7 reports an empty document without consuming the
  // token, so LoadAll loops forever, allocating (jbeder/yaml-cpp#1040, fixed upstream after 0.8). YAML::Load
  // alone would accept such a file as an empty scene.
  std::istringstream in(text);
  YAML::Parser parser(in);
  DocumentStarts documents;
  while (documents.starts.size() < 2 && parser.HandleNextDocument(documents)) {
  }
  if (documents.starts.size() >= 2) {
    const YAML::Mark &m = documents.starts[1];
    const bool separator = m.pos >= 0 && text.compare(size_t(m.pos), 3, "---") == 0;
    if (separator)
      throw ParseFailure{format_error(display_name, m.line + 1, m.column + 1, "scene",
                                      "a scene file holds one YAML document, found a second one")};
    // yaml-cpp reports the stray token as the start of a new document that has no node.
    std::string what = "unexpected content";
    if (m.pos >= 0 && size_t(m.pos) < text.size())
      what = "unexpected '" + text.substr(size_t(m.pos), 1) + "'";
    throw ParseFailure{format_error(display_name, m.line + 1, m.column + 1, "YAML syntax", what)};
  }
  return YAML::Load(text);
}

}  // namespace nimbus::scene_yaml
