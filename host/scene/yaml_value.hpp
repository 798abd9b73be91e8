// Typed, located access to a parsed YAML document. Every value remembers the file, its line and column
// and the key path that led to it ("objects[2].radius"), so that any complaint about it becomes one line
//   FILE:LINE:COLUMN: error: KEY.PATH: MESSAGE
// The section readers (sections.hpp) only ever talk to YAML through these two classes.
#pragma once

#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <yaml-cpp/yaml.h>

#include <nimbus/cpp/math.hpp>
#include "scene/scene_desc.hpp"
#include "scene/source_log.hpp"

namespace nimbus::scene_yaml {

// The first problem found in a scene, already formatted. The readers are a recursive descent that stops at
// the first error; throwing this unwinds it to parse_scene_file/parse_scene_string, which catch it and
// return it as an Error value. It never leaves the parser.
struct ParseFailure {
  std::string message;
};

// Where the YAML text came from: the name printed in errors and the directory relative asset paths
// (mesh files, included files) resolve against.
struct SceneSource {
  std::string display_name;
  std::filesystem::path base_dir;
  std::filesystem::path file;  // the file the text was read from; empty for text given directly
  SourceLog *log = nullptr;    // where the files this one names (includes, meshes) are recorded as read

  std::filesystem::path resolve(const std::string &relative_or_absolute) const;
};

// "FILE:LINE:COLUMN: error: WHAT: MESSAGE" with 1-based line and column; "FILE: error: ..." when the
// position is unknown (line <= 0).
std::string format_error(std::string_view file, int line, int column, std::string_view what,
                         std::string_view message);

// Allowed interval for a number; produces the "must be ..." wording of range errors.
struct Range {
  double lo = -kInfinity, hi = kInfinity;
  bool lo_open = false, hi_open = false;

  static Range at_least(double lo) { return {lo, kInfinity, false, false}; }
  static Range greater_than(double lo) { return {lo, kInfinity, true, false}; }
  static Range closed(double lo, double hi) { return {lo, hi, false, false}; }
  static Range open(double lo, double hi) { return {lo, hi, true, true}; }
  static Range any() { return {}; }

  bool contains(double x) const;
  std::string describe() const;  // "must be > 0", "must be in [0, 1]"
};

class YamlMap;

class YamlValue {
 public:
  YamlValue(const SceneSource &source, YAML::Node node, std::string path, YAML::Mark mark);

  const std::string &path() const { return path_; }
  int line() const { return mark_.line + 1; }
  int column() const { return mark_.column + 1; }
  SourceLocation location() const;
  const SceneSource &source() const { return *source_; }
  [[noreturn]] void fail(std::string_view message) const;
  // The line of a warning about this value, formatted as fail() formats an error (SceneDesc::warnings).
  std::string warning(std::string_view message) const;

  bool is_null() const { return node_.IsNull(); }
  bool is_map() const { return node_.IsMap(); }
  bool is_sequence() const { return node_.IsSequence(); }
  bool is_scalar() const { return node_.IsScalar(); }
  // The scalar exactly as written (empty for non-scalars); quoted in messages as "(got ...)".
  const std::string &text() const;
  // text() shortened for messages (see abbreviate).
  std::string shown() const;
  // What the value is, for "expected X, got Y": "null", "a map", "a sequence", "'abc'", "the string "1"".
  std::string describe() const;

  double number(Range range = Range::any()) const;
  float real(Range range = Range::any()) const;  // a number that must also fit a 32-bit float
  int64_t integer(Range range = Range::any()) const;
  bool boolean() const;
  std::string string() const;
  std::string nonempty_string() const;

  std::vector<YamlValue> sequence() const;
  // A sequence of exactly n elements; `shape` names the expected form in the error, e.g. "[x, y, z]".
  std::vector<YamlValue> sequence_of(size_t n, std::string_view shape) const;
  Vec3f vec3(Range range = Range::any()) const;
  Vec2f vec2(Range range = Range::any()) const;
  // An RGB triple, or one number meaning grey.
  Rgb rgb(Range range = Range::any()) const;

  // A map with any keys (e.g. material names); duplicate and non-scalar keys are errors.
  YamlMap map() const;
  // A map whose keys must all be in `allowed`.
  YamlMap map(std::initializer_list<std::string_view> allowed) const;

 private:
  const SceneSource *source_;
  YAML::Node node_;
  std::string path_;
  YAML::Mark mark_;
};

class YamlMap {
 public:
  struct Entry {
    std::string key;
    YamlValue key_value;  // the key itself, for errors reported at the key
    YamlValue value;
  };

  explicit YamlMap(YamlValue self, std::vector<Entry> entries)
      : self_(std::move(self)), entries_(std::move(entries)) {}

  const YamlValue &self() const { return self_; }
  const std::vector<Entry> &entries() const { return entries_; }
  bool has(std::string_view key) const { return find(key) != nullptr; }
  std::optional<YamlValue> get(std::string_view key) const;
  // A key that must be present; a missing one is reported at the position of this map, followed by `why`
  // when given.
  YamlValue require(std::string_view key, std::string_view why = {}) const;
  // The key node, for errors that are about the key's presence (e.g. conflicting keys).
  const YamlValue &key(std::string_view key) const;
  // Fails at the first key (in document order) that is not in `allowed`. `context` qualifies the list,
  // e.g. "a sphere" gives "unknown key 'size' for a sphere; allowed: ...".
  void check_keys(std::initializer_list<std::string_view> allowed, std::string_view context = {}) const;
  void check_keys(const std::vector<std::string_view> &allowed, std::string_view context = {}) const;
  // Path of a child key, for errors about a key that is absent.
  std::string child_path(std::string_view key) const;

 private:
  const Entry *find(std::string_view key) const;

  YamlValue self_;
  std::vector<Entry> entries_;
};

// User text as echoed in messages: at most 40 characters of its first line, "..." when cut.
std::string abbreviate(std::string_view text);

// Shortest text that reads back as the same double ("0.5", "1e-07"), for numbers in messages.
std::string format_number(double x);

// "a, b, c" — for lists of allowed names in messages.
std::string join_names(const std::vector<std::string_view> &names);

}  // namespace nimbus::scene_yaml
