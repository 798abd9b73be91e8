#include "scene/mtl_reader.hpp"

#include <algorithm>
#include <array>
#include <cfloat>
#include <charconv>
#include <cmath>
#include <map>
#include <utility>

#include "core/one_line.hpp"

namespace nimbus {

namespace {

// The first malformed statement. Thrown inside this file only, so that the value readers below can stop
// the whole file from any depth; parse_mtl turns it into its Error.
struct Malformed {
  std::string reason;
};

bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

// The line's words, as views into it (their positions tell where a file name starts).
std::vector<std::string_view> words_of(std::string_view line) {
  std::vector<std::string_view> words;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_blank(line[i])) ++i;
    const size_t start = i;
    while (i < line.size() && !is_blank(line[i])) ++i;
    if (i > start) words.push_back(line.substr(start, i - start));
  }
  return words;
}

std::optional<double> number_of(std::string_view word) {
  if (word.size() > 1 && word.front() == '+') word.remove_prefix(1);  // from_chars takes no '+'
  double x = 0;
  const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), x);
  if (end != word.data() + word.size()) return std::nullopt;
  if (ec == std::errc::result_out_of_range) return HUGE_VAL;  // "1e999": a number, though not a finite one
  if (ec != std::errc()) return std::nullopt;
  return x;
}

// How many values follow a texture option of a `map_*` statement (-o, -s and -t: one to three numbers);
// 0 for a word that is no option.
int texture_option_values(std::string_view word) {
  for (std::string_view option : {"-blendu", "-blendv", "-boost", "-bm", "-cc", "-clamp", "-colorspace",
                                  "-imfchan", "-texres", "-type"})
    if (word == option) return 1;
  if (word == "-mm") return 2;
  if (word == "-o" || word == "-s" || word == "-t") return 3;
  return 0;
}

class Reader {
 public:
  explicit Reader(const std::filesystem::path &path) : path_(path) {}

  MtlFile read(std::string_view text) {
    for (size_t start = 0; start < text.size(); ++line_) {
      const size_t end = std::min(text.find('\n', start), text.size());
      statement(text.substr(start, end - start));
      start = end + 1;
    }
    return std::move(file_);
  }

 private:
  [[noreturn]] void fail(std::string_view keyword, const std::string &reason) const {
    throw Malformed{path_.string() + ":" + std::to_string(line_) + ": " + shown(keyword) + ": " + reason};
  }

  void ignore(std::string statement) {
    if (std::find(file_.ignored.begin(), file_.ignored.end(), statement) == file_.ignored.end())
      file_.ignored.push_back(std::move(statement));
  }

  void statement(std::string_view line) {
    std::vector<std::string_view> words = words_of(line);
    if (words.empty() || words.front().front() == '#') return;
    const std::string_view keyword = words.front();
    if (keyword == "newmtl") return new_material(words);
    if (keyword == "Ka") return;  // ambient light has no physical meaning in Nimbus: dropped silently
    constexpr std::array<std::string_view, 10> kMapped{"Kd", "Ks", "Ke", "Tf",    "Ns",
                                                       "Ni", "d",  "Tr", "illum", "map_Kd"};
    if (std::find(kMapped.begin(), kMapped.end(), keyword) == kMapped.end()) return ignore(shown(keyword));
    if (file_.materials.empty()) fail(keyword, "comes before any 'newmtl'");
    MtlMaterial &m = file_.materials.back();
    if (keyword == "map_Kd") return texture(line, words, m.map_kd);
    // A trailing comment is not a value.
    words.erase(std::find_if(words.begin(), words.end(), [](std::string_view w) { return w.front() == '#'; }),
                words.end());
    const std::vector<std::string_view> values(words.begin() + 1, words.end());
    if (keyword == "Kd") return color(keyword, values, m.kd);
    if (keyword == "Ks") return color(keyword, values, m.ks);
    if (keyword == "Ke") return color(keyword, values, m.ke);
    if (keyword == "Tf") return color(keyword, values, m.tf);
    if (keyword == "illum") return illum(values, m.illum);
    if (keyword == "d" && !values.empty() && values.front() == "-halo") return ignore("d -halo");
    scalar(keyword, values, keyword == "Ns" ? m.ns : keyword == "Ni" ? m.ni : keyword == "d" ? m.d : m.tr);
  }

  void new_material(const std::vector<std::string_view> &words) {
    // The name is one word, as `usemtl` reads it (tinyobjloader takes the first word there).
    if (words.size() < 2) fail("newmtl", "no material name");
    const std::string name(words[1]);
    if (const auto [it, added] = lines_.try_emplace(name, line_); !added)
      fail("newmtl",
           "material '" + shown(name) + "' is already defined on line " + std::to_string(it->second));
    file_.materials.emplace_back().name = name;
  }

  float real(std::string_view keyword, std::string_view word) const {
    const std::optional<double> x = number_of(word);
    if (!x) fail(keyword, "expected a number, got '" + shown(word) + "'");
    if (!std::isfinite(*x) || std::abs(*x) > FLT_MAX)
      fail(keyword, "'" + shown(word) + "' is not a finite single-precision number");
    return float(*x);
  }

  void scalar(std::string_view keyword, const std::vector<std::string_view> &values,
              std::optional<float> &out) {
    if (values.size() != 1)
      fail(keyword, "expected one number, got " + std::to_string(values.size()) + " values");
    out = real(keyword, values[0]);
  }

  // `K? r g b` or `K? r` (grey); the spectral and CIE XYZ forms are named as ignored.
  void color(std::string_view keyword, const std::vector<std::string_view> &values, std::optional<Rgb> &out) {
    if (!values.empty() && (values[0] == "spectral" || values[0] == "xyz"))
      return ignore(std::string(keyword) + " " + std::string(values[0]));
    if (values.size() != 1 && values.size() != 3)
      fail(keyword, "expected r g b or one number, got " + std::to_string(values.size()) + " values");
    if (values.size() == 1) {
      out = Rgb(real(keyword, values[0]));
    } else {
      out = Rgb{real(keyword, values[0]), real(keyword, values[1]), real(keyword, values[2])};
    }
  }

  void illum(const std::vector<std::string_view> &values, std::optional<int> &out) {
    if (values.size() != 1)
      fail("illum", "expected one integer, got " + std::to_string(values.size()) + " values");
    int model = 0;
    const std::string_view word = values[0];
    const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), model);
    if (ec != std::errc() || end != word.data() + word.size())
      fail("illum", "expected an integer, got '" + shown(word) + "'");
    out = model;
  }

  // `map_Kd [options] FILE`: the options are named as ignored, and the rest of the line is the file name,
  // which may hold spaces. Backslashes are taken for the directory separators of files written on Windows.
  void texture(std::string_view line, const std::vector<std::string_view> &words, std::string &out) {
    size_t i = 1;
    while (i + 1 < words.size()) {
      const int values = texture_option_values(words[i]);
      if (values == 0) break;
      ignore("map_Kd " + std::string(words[i]));
      ++i;
      for (int n = 0; n < values && i + 1 < words.size(); ++n, ++i)
        if (values == 3 && n > 0 && !number_of(words[i])) break;  // fewer than 3 numbers
    }
    if (i >= words.size()) fail("map_Kd", "no file name");
    std::string name(line.substr(size_t(words[i].data() - line.data())));
    while (!name.empty() && is_blank(name.back())) name.pop_back();
    std::replace(name.begin(), name.end(), '\\', '/');
    const std::filesystem::path file = path_.parent_path() / name;
    std::error_code ec;
    const std::filesystem::path absolute = std::filesystem::absolute(file, ec);
    out = (ec ? file : absolute).lexically_normal().string();
  }

  std::filesystem::path path_;
  int line_ = 1;
  MtlFile file_;
  std::map<std::string, int> lines_;  // the line of each material's `newmtl`
};

}  // namespace

Expected<MtlFile> parse_mtl(std::string_view text, const std::filesystem::path &path) {
  try {
    return Reader(path).read(text);
  } catch (const Malformed &m) {
    return Error{m.reason};
  }
}

}  // namespace nimbus
