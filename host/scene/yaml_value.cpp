#include "scene/yaml_value.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>

namespace nimbus::scene_yaml {

namespace {

std::string lowercase(std::string_view s) {
  std::string out(s);
  for (char &c : out) c = char(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

// YAML writes infinities and NaN as .inf/.nan; std::from_chars spells them inf/nan. Both parse, so that
// the error can say "must be finite" rather than "expected a number".
std::optional<double> parse_double(std::string_view s) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  const std::string lower = lowercase(s);
  if (lower == ".inf") return std::numeric_limits<double>::infinity();
  if (lower == "-.inf") return -std::numeric_limits<double>::infinity();
  if (lower == ".nan") return std::numeric_limits<double>::quiet_NaN();
  if (s.empty()) return std::nullopt;
  double x = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), x);
  if (end != s.data() + s.size()) return std::nullopt;
  if (ec == std::errc::result_out_of_range) return x < 0 ? -HUGE_VAL : HUGE_VAL;
  if (ec != std::errc()) return std::nullopt;
  return x;
}

std::string format_line(std::string_view file, int line, int column, std::string_view severity,
                        std::string_view what, std::string_view message) {
  std::string out(file);
  if (line > 0) out += ":" + std::to_string(line) + ":" + std::to_string(column);
  out += ": " + std::string(severity) + ": ";
  if (!what.empty()) out += std::string(what) + ": ";
  out += message;
  // One message, one line: a multi-line reason from a library would break the format.
  std::replace(out.begin(), out.end(), '\n', ' ');
  return out;
}

std::string join_path(const std::string &parent, std::string_view key) {
  return parent.empty() ? abbreviate(key) : parent + "." + abbreviate(key);
}

}  // namespace

// User text echoed in a message is cut at the first line break and at 40 characters: a mistyped block
// scalar or a runaway key can otherwise swallow the rest of the file into one error line.
std::string abbreviate(std::string_view text) {
  constexpr size_t kMax = 40;
  const size_t end = std::min(text.find_first_of("\r\n"), kMax);
  return end >= text.size() ? std::string(text) : std::string(text.substr(0, end)) + "...";
}

std::filesystem::path SceneSource::resolve(const std::string &relative_or_absolute) const {
  const std::filesystem::path p(relative_or_absolute);
  return p.is_absolute() ? p : base_dir / p;
}

std::string format_error(std::string_view file, int line, int column, std::string_view what,
                         std::string_view message) {
  return format_line(file, line, column, "error", what, message);
}

std::string YamlValue::warning(std::string_view message) const {
  return format_line(source_->display_name, line(), column(), "warning", path_, message);
}

std::string format_number(double x) {
  char buf[64];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, x);
  return ec == std::errc() ? std::string(buf, end) : std::to_string(x);
}

std::string join_names(const std::vector<std::string_view> &names) {
  std::string out;
  for (size_t i = 0; i < names.size(); ++i) out += (i ? ", " : "") + std::string(names[i]);
  return out;
}

bool Range::contains(double x) const {
  const bool above = lo_open ? x > lo : x >= lo;
  const bool below = hi_open ? x < hi : x <= hi;
  return above && below;
}

std::string Range::describe() const {
  if (std::isinf(hi)) return std::string(lo_open ? "must be > " : "must be >= ") + format_number(lo);
  if (std::isinf(lo)) return std::string(hi_open ? "must be < " : "must be <= ") + format_number(hi);
  return "must be in " + std::string(lo_open ? "(" : "[") + format_number(lo) + ", " + format_number(hi) +
         (hi_open ? ")" : "]");
}

YamlValue::YamlValue(const SceneSource &source, YAML::Node node, std::string path, YAML::Mark mark)
    : source_(&source), node_(std::move(node)), path_(std::move(path)), mark_(mark) {}

SourceLocation YamlValue::location() const { return {source_->display_name, line(), column()}; }

void YamlValue::fail(std::string_view message) const {
  throw ParseFailure{format_error(source_->display_name, line(), column(), path_, message)};
}

const std::string &YamlValue::text() const {
  static const std::string empty;
  return node_.IsScalar() ? node_.Scalar() : empty;
}

std::string YamlValue::shown() const { return abbreviate(text()); }

std::string YamlValue::describe() const {
  if (node_.IsNull()) return "null";
  if (node_.IsMap()) return "a map";
  if (node_.IsSequence()) return "a sequence";
  // yaml-cpp tags plain scalars "?"; quoted or explicitly tagged scalars are strings by intent.
  if (node_.Tag() != "?") return "the string \"" + shown() + "\"";
  return "'" + shown() + "'";
}

double YamlValue::number(Range range) const {
  std::optional<double> x;
  if (node_.IsScalar() && node_.Tag() == "?") x = parse_double(node_.Scalar());
  if (!x) fail("expected a number, got " + describe());
  if (!std::isfinite(*x)) fail("must be a finite number (got " + shown() + ")");
  if (!range.contains(*x)) fail(range.describe() + " (got " + shown() + ")");
  return *x;
}

float YamlValue::real(Range range) const {
  const double x = number(range);
  if (std::abs(x) > double(std::numeric_limits<float>::max()))
    fail("is too large for single precision (got " + shown() + ")");
  return float(x);
}

int64_t YamlValue::integer(Range range) const {
  if (node_.IsScalar() && node_.Tag() == "?") {
    std::string_view s = node_.Scalar();
    if (!s.empty() && s.front() == '+') s.remove_prefix(1);
    int64_t i = 0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), i);
    if (end == s.data() + s.size() && !s.empty()) {
      if (ec == std::errc::result_out_of_range) fail("integer out of range (got " + shown() + ")");
      if (ec == std::errc()) {
        if (!range.contains(double(i))) fail(range.describe() + " (got " + shown() + ")");
        return i;
      }
    }
    if (parse_double(node_.Scalar())) fail("expected an integer, got " + shown());
  }
  fail("expected an integer, got " + describe());
}

bool YamlValue::boolean() const {
  if (node_.IsScalar() && node_.Tag() == "?") {
    // The YAML 1.1 spellings yaml-cpp itself accepts, so `on`/`off` keep working.
    const std::string s = lowercase(node_.Scalar());
    if (s == "true" || s == "yes" || s == "on") return true;
    if (s == "false" || s == "no" || s == "off") return false;
  }
  fail("expected true or false, got " + describe());
}

std::string YamlValue::string() const {
  if (!node_.IsScalar()) fail("expected a string, got " + describe());
  return node_.Scalar();
}

std::string YamlValue::nonempty_string() const {
  std::string s = string();
  if (s.empty()) fail("must not be empty");
  return s;
}

std::vector<YamlValue> YamlValue::sequence() const {
  if (!node_.IsSequence()) fail("expected a sequence, got " + describe());
  std::vector<YamlValue> out;
  out.reserve(node_.size());
  size_t i = 0;
  for (const YAML::Node &child : node_) {
    // An empty entry ("[1, , 2]" or "- " alone) has no position of its own: point at the sequence.
    const YAML::Mark mark = child.IsNull() ? mark_ : child.Mark();
    out.emplace_back(*source_, child, path_ + "[" + std::to_string(i++) + "]", mark);
  }
  return out;
}

std::vector<YamlValue> YamlValue::sequence_of(size_t n, std::string_view shape) const {
  if (!node_.IsSequence()) fail("expected " + std::string(shape) + ", got " + describe());
  std::vector<YamlValue> items = sequence();
  if (items.size() != n)
    fail("expected " + std::string(shape) + " (" + std::to_string(n) + " elements), got " +
         std::to_string(items.size()) + " element" + (items.size() == 1 ? "" : "s"));
  return items;
}

Vec3f YamlValue::vec3(Range range) const {
  const std::vector<YamlValue> v = sequence_of(3, "[x, y, z]");
  return {v[0].real(range), v[1].real(range), v[2].real(range)};
}

Vec2f YamlValue::vec2(Range range) const {
  const std::vector<YamlValue> v = sequence_of(2, "[u, v]");
  return {v[0].real(range), v[1].real(range)};
}

Rgb YamlValue::rgb(Range range) const {
  if (node_.IsScalar()) return Rgb(real(range));
  if (!node_.IsSequence()) fail("expected [r, g, b] or a single number, got " + describe());
  const std::vector<YamlValue> v = sequence_of(3, "[r, g, b]");
  return {v[0].real(range), v[1].real(range), v[2].real(range)};
}

YamlMap YamlValue::map() const {
  if (!node_.IsMap()) fail("expected a map, got " + describe());
  std::vector<YamlMap::Entry> entries;
  for (const auto &kv : node_) {
    YamlValue key(*source_, kv.first, path_, kv.first.Mark());
    if (!kv.first.IsScalar()) key.fail("map keys must be names, got " + key.describe());
    const std::string &name = kv.first.Scalar();
    // yaml-cpp keeps both entries of a repeated key and lookups would silently take the first.
    for (const YamlMap::Entry &e : entries)
      if (e.key == name)
        YamlValue(*source_, kv.first, join_path(path_, name), kv.first.Mark())
            .fail("duplicate key '" + abbreviate(name) + "' (first at line " +
                  std::to_string(e.key_value.line()) + ", column " + std::to_string(e.key_value.column()) +
                  ")");
    const std::string child = join_path(path_, name);
    // An empty value ("radius:") gets the position of whatever follows it; the key is where the user looks.
    const YAML::Mark value_mark = kv.second.IsNull() ? kv.first.Mark() : kv.second.Mark();
    entries.push_back({name, YamlValue(*source_, kv.first, child, kv.first.Mark()),
                       YamlValue(*source_, kv.second, child, value_mark)});
  }
  return YamlMap(*this, std::move(entries));
}

YamlMap YamlValue::map(std::initializer_list<std::string_view> allowed) const {
  YamlMap m = map();
  m.check_keys(allowed);
  return m;
}

const YamlMap::Entry *YamlMap::find(std::string_view key) const {
  for (const Entry &e : entries_)
    if (e.key == key) return &e;
  return nullptr;
}

std::optional<YamlValue> YamlMap::get(std::string_view key) const {
  const Entry *e = find(key);
  return e ? std::optional<YamlValue>(e->value) : std::nullopt;
}

YamlValue YamlMap::require(std::string_view key, std::string_view why) const {
  const Entry *e = find(key);
  if (!e) {
    throw ParseFailure{format_error(
        self_.source().display_name, self_.line(), self_.column(), child_path(key),
        "missing required key '" + std::string(key) + "'" + (why.empty() ? "" : ": " + std::string(why)))};
  }
  return e->value;
}

const YamlValue &YamlMap::key(std::string_view key) const {
  const Entry *e = find(key);
  if (!e) self_.fail("internal: key '" + std::string(key) + "' looked up but absent");
  return e->key_value;
}

void YamlMap::check_keys(std::initializer_list<std::string_view> allowed, std::string_view context) const {
  check_keys(std::vector<std::string_view>(allowed), context);
}

void YamlMap::check_keys(const std::vector<std::string_view> &allowed, std::string_view context) const {
  for (const Entry &e : entries_) {
    if (std::find(allowed.begin(), allowed.end(), e.key) != allowed.end()) continue;
    std::string message = "unknown key '" + abbreviate(e.key) + "'";
    if (!context.empty()) message += " for " + std::string(context);
    message += "; allowed: " + join_names(allowed);
    e.key_value.fail(message);
  }
}

std::string YamlMap::child_path(std::string_view key) const { return join_path(self_.path(), key); }

}  // namespace nimbus::scene_yaml
