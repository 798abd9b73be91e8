// `render:` — image size, stopping rule, seed, path length, integrator and its options, film elements,
// pixel filter, render region and light sampler.
#include <algorithm>
#include <optional>
#include <string>

#include "core/limits.hpp"
#include "scene/pixel_filter_type.hpp"
#include "scene/sections.hpp"

namespace nimbus::scene_yaml {

namespace {

constexpr int64_t kMaxDepth = 1024;

// The render section's own keys; any other key is an option of the bound integrator.
const std::vector<std::string_view> kRenderKeys{"resolution", "iterations", "time",          "target_error",
                                                "seed",       "max_depth",  "integrator",    "elements",
                                                "filter",     "region",     "light_sampler", "guide"};

// [x0, y0, x1, y1] in pixels, half-open ([x0, x1) x [y0, y1)), inside the image. Checked against the
// resolution of the same section, so the order of the keys does not matter.
void read_region(const YamlValue &v, RenderDesc &r) {
  const std::vector<YamlValue> c = v.sequence_of(4, "[x0, y0, x1, y1]");
  const uint32_t size[2] = {r.width, r.height};
  for (int i = 0; i < 4; ++i) {
    const uint32_t limit = size[i % 2];
    r.region[i] = uint32_t(c[size_t(i)].integer(Range::closed(0, double(limit))));
  }
  if (r.region[2] <= r.region[0]) c[2].fail("x1 must be greater than x0 (got " + c[0].shown() + ")");
  if (r.region[3] <= r.region[1]) c[3].fail("y1 must be greater than y0 (got " + c[1].shown() + ")");
}

}  // namespace

RenderDesc read_render(const YamlValue &section) {
  RenderDesc r;
  if (section.is_null()) return r;  // `render:` with nothing under it: all defaults
  const YamlMap m = section.map();
  // Keys the host does not know are the bound integrator's options, checked against its declarations
  // once it is bound (so an unknown key is reported with the integrator's options beside the host's).
  for (const YamlMap::Entry &e : m.entries()) {
    if (std::find(kRenderKeys.begin(), kRenderKeys.end(), e.key) != kRenderKeys.end()) continue;
    if (!e.value.is_scalar())
      e.value.fail("expected a value for the integrator's option, got " + e.value.describe());
    const SourceLocation at = e.key_value.location();
    r.options.push_back({e.key, e.value.text(), at.text() + ": " + e.key_value.path(),
                         "the render section's own keys: " + join_names(kRenderKeys)});
  }

  if (auto v = m.get("resolution")) {
    const std::vector<YamlValue> wh = v->sequence_of(2, "[width, height]");
    r.width = uint32_t(wh[0].integer(Range::closed(1, kMaxResolution)));
    r.height = uint32_t(wh[1].integer(Range::closed(1, kMaxResolution)));
  }
  if (auto v = m.get("iterations")) r.iterations = uint64_t(v->integer(Range::at_least(1)));
  if (auto v = m.get("time")) r.time_seconds = v->number(Range::greater_than(0));
  if (auto v = m.get("target_error")) r.target_error = v->number(Range::greater_than(0));
  if (auto v = m.get("seed")) r.seed = uint64_t(v->integer(Range::at_least(0)));
  if (auto v = m.get("max_depth")) r.max_depth = uint32_t(v->integer(Range::closed(1, kMaxDepth)));
  if (auto v = m.get("integrator")) r.integrator = v->nonempty_string();
  if (auto v = m.get("elements")) {
    for (const YamlValue &e : v->sequence()) {
      std::string name = e.nonempty_string();
      // A repeated element would be allocated or written twice downstream; it is always a typo.
      if (std::find(r.elements.begin(), r.elements.end(), name) != r.elements.end())
        e.fail("element '" + abbreviate(name) + "' is listed twice");
      r.elements.push_back(std::move(name));
    }
  }
  if (auto v = m.get("filter")) {
    const std::string name = v->string();
    const std::optional<FilterType> filter = filter_from_name(name);
    if (!filter) v->fail("unknown pixel filter '" + abbreviate(name) + "'; known: " + filter_names());
    r.filter = *filter;
  }
  if (auto v = m.get("region")) read_region(*v, r);
  // A plugin id; whether such a plugin exists is only known once plugins are loaded.
  if (auto v = m.get("light_sampler")) r.light_sampler = v->nonempty_string();
  if (auto v = m.get("guide")) {
    r.guide = v->nonempty_string();
    r.guide_where = v->location().text() + ": " + v->path();
  }
  return r;
}

}  // namespace nimbus::scene_yaml
