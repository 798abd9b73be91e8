// A dielectric's index of refraction in `materials:`: a constant `ior`, or a dispersive glass.
//
//   glass:   { type: dielectric, ior: 1.5 }                                   # n at every wavelength
//   crown:   { type: dielectric, ior: 1.5168, abbe: 64.17 }                   # n_d and Abbe number V_d
//   flint:   { type: dielectric, cauchy: [1.67, 0.0104] }                     # A + B / l^2 (+ C / l^4)
//   bk7:     { type: dielectric, sellmeier: { b: [1.0396, 0.2318, 1.0105], c: [0.0060, 0.0200, 103.56] } }
//
//   ior: n            in [1, 10]; with `abbe`, n_d (the index at 587.56 nm; default 1.5).
//   abbe: V_d         > 0; (n_d - 1) / (n_F - n_C): smaller disperses more. A two-term Cauchy curve.
//   cauchy: [A, B] or [A, B, C]          lambda in um: B in um^2, C in um^4.
//   sellmeier: { b: [B1, B2, B3], c: [C1, C2, C3] }   n^2 = 1 + sum B_i l^2 / (l^2 - C_i), C_i in um^2.
//
// At most one of abbe, cauchy and sellmeier, and no `ior` beside a curve that gives the index itself: one
// of two would be silently ignored. The curve must be finite and above 1 from 360 to 830 nm. Paths that
// carry RGB (scenes without dispersion, plugins built before SDK 1.7) use the index at 587.56 nm.
#include <array>
#include <string>
#include <string_view>

#include "scene/sections.hpp"

namespace nimbus::scene_yaml {

namespace {

std::array<double, 3> three_numbers(const YamlValue &v, std::string_view shape) {
  const std::vector<YamlValue> items = v.sequence_of(3, shape);
  return {items[0].number(), items[1].number(), items[2].number()};
}

IorCurve read_cauchy(const YamlValue &v) {
  const std::vector<YamlValue> items = v.sequence();
  if (items.size() != 2 && items.size() != 3)
    v.fail("expected [A, B] or [A, B, C] (B in um^2, C in um^4), got " + std::to_string(items.size()) +
           " element" + (items.size() == 1 ? "" : "s"));
  return IorCurve::cauchy(items[0].number(), items[1].number(), items.size() == 3 ? items[2].number() : 0);
}

IorCurve read_sellmeier(const YamlValue &v) {
  const YamlMap m = v.map({"b", "c"});
  return IorCurve::sellmeier(three_numbers(m.require("b"), "[B1, B2, B3]"),
                             three_numbers(m.require("c"), "[C1, C2, C3] (um^2)"));
}

}  // namespace

void read_dielectric_index(const YamlMap &m, MaterialDesc &mat) {
  // The curve keys, then whether each conflicts with `ior` (abbe takes it as n_d).
  const auto is_curve = [](std::string_view key) {
    return key == "abbe" || key == "cauchy" || key == "sellmeier";
  };
  const YamlMap::Entry *curve = nullptr, *ior = nullptr;
  for (const YamlMap::Entry &e : m.entries()) {
    if (is_curve(e.key)) {
      if (curve)
        e.key_value.fail("conflicts with '" + curve->key + "'; give one of abbe, cauchy and sellmeier");
      if (ior && e.key != "abbe")
        e.key_value.fail("conflicts with 'ior'; the " + e.key + " curve gives the index at every wavelength");
      curve = &e;
    } else if (e.key == "ior") {
      if (curve && curve->key != "abbe")
        e.key_value.fail("conflicts with '" + curve->key + "', which gives the index at every wavelength");
      ior = &e;
    }
  }
  // Relative IORs below 1 (e.g. an air bubble in water) need nested media, which v0 does not model.
  if (ior) mat.ior = ior->value.real(Range::closed(1, 10));
  if (!curve) return;
  IorCurve c;
  if (curve->key == "abbe")
    c = IorCurve::abbe(mat.ior, curve->value.real(Range::greater_than(0)));
  else if (curve->key == "cauchy")
    c = read_cauchy(curve->value);
  else
    c = read_sellmeier(curve->value);
  if (Status s = c.validate(); !s) curve->key_value.fail(s.error().message);
  mat.dispersion = c;
  if (curve->key != "abbe") mat.ior = c.at(float(kFraunhoferD));  // abbe's n_d is `ior` already
}

}  // namespace nimbus::scene_yaml
