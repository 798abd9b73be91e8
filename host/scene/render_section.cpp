// `render:` — image size, stopping rule, seed, path length, integrator and its options, film elements.
#include <algorithm>
#include <cctype>
#include <string>

#include "scene/sections.hpp"

namespace nimbus::scene_yaml {

namespace {

constexpr int64_t kMaxResolution = 16384;
constexpr int64_t kMaxDepth = 1024;

// `caustics: on|off` is the only integrator option v0 knows. Kept as written in RenderDesc::options
// ("on"/"off"); YAML booleans are accepted because `on` and `true` read the same to users.
std::string read_switch(const YamlValue &v) {
  if (v.is_scalar()) {
    std::string s = v.text();
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    if (s == "on" || s == "true" || s == "yes") return "on";
    if (s == "off" || s == "false" || s == "no") return "off";
  }
  v.fail("expected on or off, got " + v.describe());
}

}  // namespace

RenderDesc read_render(const YamlValue &section) {
  RenderDesc r;
  if (section.is_null()) return r;  // `render:` with nothing under it: all defaults
  const YamlMap m = section.map(
      {"resolution", "iterations", "time", "seed", "max_depth", "integrator", "elements", "caustics"});

  if (auto v = m.get("resolution")) {
    const std::vector<YamlValue> wh = v->sequence_of(2, "[width, height]");
    r.width = uint32_t(wh[0].integer(Range::closed(1, kMaxResolution)));
    r.height = uint32_t(wh[1].integer(Range::closed(1, kMaxResolution)));
  }
  if (auto v = m.get("iterations")) r.iterations = uint64_t(v->integer(Range::at_least(1)));
  if (auto v = m.get("time")) r.time_seconds = v->number(Range::greater_than(0));
  if (auto v = m.get("seed")) r.seed = uint64_t(v->integer(Range::at_least(0)));
  if (auto v = m.get("max_depth")) r.max_depth = uint32_t(v->integer(Range::closed(1, kMaxDepth)));
  if (auto v = m.get("integrator")) r.integrator = v->nonempty_string();
  if (auto v = m.get("caustics")) r.options["caustics"] = read_switch(*v);
  if (auto v = m.get("elements")) {
    for (const YamlValue &e : v->sequence()) {
      std::string name = e.nonempty_string();
      // A repeated element would be allocated or written twice downstream; it is always a typo.
      if (std::find(r.elements.begin(), r.elements.end(), name) != r.elements.end())
        e.fail("element '" + abbreviate(name) + "' is listed twice");
      r.elements.push_back(std::move(name));
    }
  }
  return r;
}

}  // namespace nimbus::scene_yaml
