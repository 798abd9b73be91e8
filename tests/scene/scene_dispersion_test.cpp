// Dispersive dielectrics in `materials:` (scene/dielectric_section.cpp): each way of giving the index over
// wavelength parses to the curve it names, checked at the Fraunhofer F, d and C lines against values
// worked out by hand from the equations (and, for N-BK7, Schott's catalogue); each mistake is named at
// file:line:column.
#include <gtest/gtest.h>

#include "scene_test_support.hpp"

namespace nimbus::test {
namespace scene_dispersion_test {

const std::string kHead = "materials:\n  g:\n    type: dielectric\n";

// The curve of the single material of `yaml`, which must be a dispersive dielectric.
IorCurve curve_of(const std::string &yaml) {
  const SceneDesc scene = parse_ok(yaml);
  EXPECT_EQ(scene.materials.size(), 1u);
  if (scene.materials.empty()) return {};
  const MaterialDesc &m = scene.materials[0];
  EXPECT_TRUE(m.dispersive());
  EXPECT_TRUE(m.dispersion.has_value());
  // The RGB path's index is the curve's n_d, so a plugin that knows no wavelengths sees the same glass.
  EXPECT_FLOAT_EQ(m.ior, m.ior_curve().at(587.56f));
  return m.ior_curve();
}

// Indices at F (486.13 nm), d (587.56 nm) and C (656.27 nm). The expected values are the equations
// evaluated in double outside the renderer; 1e-9 leaves room for the order of operations only.
void expect_fdc(const IorCurve &c, double n_f, double n_d, double n_c, double tolerance = 1e-9) {
  EXPECT_NEAR(c.index(kFraunhoferF), n_f, tolerance);
  EXPECT_NEAR(c.index(kFraunhoferD), n_d, tolerance);
  EXPECT_NEAR(c.index(kFraunhoferC), n_c, tolerance);
}

TEST(SceneDispersion, AbbeTakesIorAsNd) {
  // n_d = 1.5 (exact in float), V_d = 40: n_F - n_C must come out as (n_d - 1) / V_d = 0.0125.
  const IorCurve c = curve_of(kHead + "    ior: 1.5\n    abbe: 40\n");
  EXPECT_EQ(c.model(), IorCurve::Model::kAbbe);
  expect_fdc(c, 1.5087375843884825, 1.5, 1.4962375843884825);
  EXPECT_NEAR(abbe_number(c), 40, 1e-6);
}

TEST(SceneDispersion, AbbeWithoutIorUsesTheDefaultNd) {
  const IorCurve c = curve_of(kHead + "    abbe: 30\n");
  EXPECT_NEAR(c.index(kFraunhoferD), 1.5, 1e-9);
  EXPECT_NEAR(abbe_number(c), 30, 1e-4);
}

TEST(SceneDispersion, CauchyTwoAndThreeTerms) {
  const IorCurve two = curve_of(kHead + "    cauchy: [1.5046, 0.0042]\n");
  EXPECT_EQ(two.model(), IorCurve::Model::kCauchy);
  expect_fdc(two, 1.5223723330947083, 1.5167659169117187, 1.5143517865487148);
  const IorCurve three = curve_of(kHead + "    cauchy: [1.458, 0.00354, 0.0001]\n    roughness: 0.2\n");
  expect_fdc(three, 1.4747701037877012, 1.4690931862853582, 1.466758463520151);
}

TEST(SceneDispersion, SellmeierMatchesSchottNbk7) {
  const IorCurve c = curve_of(kHead +
                              "    sellmeier:\n      b: [1.03961212, 0.231792344, 1.01046945]\n"
                              "      c: [0.00600069867, 0.0200179144, 103.560653]\n");
  EXPECT_EQ(c.model(), IorCurve::Model::kSellmeier);
  expect_fdc(c, 1.5223764850741002, 1.5168001097398938, 1.514322425203109);
  // The catalogue prints n_F 1.52238, n_d 1.51680, n_C 1.51432, rounded to 5 decimals.
  expect_fdc(c, 1.52238, 1.51680, 1.51432, 0.5e-5 + 1e-7);
}

TEST(SceneDispersion, PlainIorIsNotDispersive) {
  const SceneDesc scene = parse_ok(kHead + "    ior: 1.7\n");
  const MaterialDesc &m = scene.materials.at(0);
  EXPECT_FALSE(m.dispersion.has_value());
  EXPECT_FALSE(m.dispersive());
  EXPECT_FLOAT_EQ(m.ior, 1.7f);
  EXPECT_EQ(m.ior_curve().at(400), 1.7f);  // exactly the RGB index at every wavelength
  EXPECT_EQ(m.ior_curve().at(700), 1.7f);
  // A Cauchy curve without its wavelength terms is a curve, but a constant one: no wavelengths needed.
  const SceneDesc flat = parse_ok(kHead + "    cauchy: [1.6, 0]\n");
  EXPECT_FALSE(flat.materials.at(0).dispersive());
  EXPECT_FLOAT_EQ(flat.materials.at(0).ior, 1.6f);
}

TEST(SceneDispersionErrors, TwoCurves) {
  EXPECT_TRUE(fails_at(kHead + "    abbe: 40\n    cauchy: [1.5, 0.004]\n", 5, 5, "materials.g.cauchy",
                       "conflicts with 'abbe'; give one of abbe, cauchy and sellmeier"));
  EXPECT_TRUE(fails_at(kHead + "    sellmeier: { b: [1, 0, 0], c: [0.01, 0, 0] }\n    abbe: 40\n", 5, 5,
                       "materials.g.abbe", "conflicts with 'sellmeier'"));
}

TEST(SceneDispersionErrors, IorBesideACurveThatGivesTheIndex) {
  EXPECT_TRUE(fails_at(kHead + "    ior: 1.5\n    cauchy: [1.5, 0.004]\n", 5, 5, "materials.g.cauchy",
                       "conflicts with 'ior'; the cauchy curve gives the index at every wavelength"));
  EXPECT_TRUE(fails_at(kHead + "    sellmeier: { b: [1, 0, 0], c: [0.01, 0, 0] }\n    ior: 1.5\n", 5, 5,
                       "materials.g.ior", "conflicts with 'sellmeier'"));
}

TEST(SceneDispersionErrors, BadValues) {
  EXPECT_TRUE(fails_at(kHead + "    abbe: 0\n", 4, 11, "materials.g.abbe", "must be > 0 (got 0)"));
  EXPECT_TRUE(fails_at(kHead + "    abbe: fast\n", 4, 11, "materials.g.abbe", "expected a number"));
  EXPECT_TRUE(fails_at(kHead + "    cauchy: [1.5]\n", 4, 13, "materials.g.cauchy",
                       "expected [A, B] or [A, B, C] (B in um^2, C in um^4), got 1 element"));
  EXPECT_TRUE(fails_at(kHead + "    cauchy: 1.5\n", 4, 13, "materials.g.cauchy", "expected a sequence"));
  EXPECT_TRUE(fails_at(kHead + "    sellmeier: { b: [1, 0], c: [0.01, 0, 0] }\n", 4, 21,
                       "materials.g.sellmeier.b", "expected [B1, B2, B3] (3 elements), got 2 elements"));
  EXPECT_TRUE(fails_at(kHead + "    sellmeier: { b: [1, 0, 0] }\n", 4, 16, "materials.g.sellmeier.c",
                       "missing required key 'c'"));
  EXPECT_TRUE(fails_at(kHead + "    sellmeier: { b: [1, 0, 0], c: [0.01, 0, 0], d: [1] }\n", 4, 49,
                       "materials.g.sellmeier.d", "unknown key 'd'"));
  EXPECT_TRUE(fails_at("materials:\n  w: { type: diffuse, abbe: 40 }\n", 2, 23, "materials.w.abbe",
                       "unknown key 'abbe'"));
}

TEST(SceneDispersionErrors, UnusableCurvesAtTheirKey) {
  // n_d must exceed 1 for the Abbe construction (ior alone may be 1: an index-matched boundary).
  EXPECT_TRUE(fails_at(kHead + "    ior: 1\n    abbe: 40\n", 5, 5, "materials.g.abbe",
                       "Abbe glass: n_d 1.000000 must be above 1"));
  // 0.9 + 0.001 / 0.36^2 = 0.9077 at 360 nm.
  EXPECT_TRUE(fails_at(kHead + "    cauchy: [0.9, 0.001]\n", 4, 5, "materials.g.cauchy",
                       "Cauchy curve: index 0.907716 at 360 nm"));
  // C = 0.25 um^2: a pole at 500 nm.
  EXPECT_TRUE(fails_at(kHead + "    sellmeier: { b: [1, 0, 0], c: [0.25, 0, 0] }\n", 4, 5,
                       "materials.g.sellmeier", "term 1 has a pole at 500.000000 nm"));
  // So strong a dispersion that the index falls below 1 in the red: V_d = 0.5 with n_d 1.5.
  EXPECT_TRUE(fails_at(kHead + "    ior: 1.5\n    abbe: 0.5\n", 5, 5, "materials.g.abbe",
                       "must be finite and above 1"));
}

}  // namespace scene_dispersion_test
}  // namespace nimbus::test
