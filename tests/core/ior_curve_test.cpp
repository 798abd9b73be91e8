// core/ior_curve.hpp: catalogue glasses against their published indices, the Abbe construction's
// exactness, and validation of unusable curves.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include <nimbus/cpp/spectral.hpp>
#include "core/ior_curve.hpp"

namespace nimbus {
namespace ior_curve_test {

// Schott's N-BK7 Sellmeier coefficients (C in um^2), from the catalogue data sheet.
IorCurve n_bk7() {
  return IorCurve::sellmeier({1.03961212, 0.231792344, 1.01046945},
                             {0.00600069867, 0.0200179144, 103.560653});
}

TEST(IorCurve, SellmeierReproducesSchottNbk7) {
  // The catalogue prints n_d 1.51680, n_F 1.52238, n_C 1.51432 (5 decimals); its Sellmeier fit is good to
  // ~1e-6 in the visible, so 1e-4 is the brief's rounding of the catalogue plus a wide margin.
  const IorCurve glass = n_bk7();
  EXPECT_NEAR(glass.at(587.56f), 1.5168, 1e-4);
  EXPECT_NEAR(glass.at(486.13f), 1.5224, 1e-4);
  EXPECT_NEAR(glass.at(656.27f), 1.5143, 1e-4);
  EXPECT_NEAR(abbe_number(glass), 64.17, 0.05);  // catalogue V_d
  EXPECT_TRUE(glass.dispersive());
  EXPECT_TRUE(glass.validate().ok());
}

TEST(IorCurve, AbbeMatchesNdAndVdExactly) {
  for (auto [n_d, v_d] : {std::pair{1.5168, 64.17}, std::pair{1.7847, 25.72}, std::pair{2.417, 55.3}}) {
    const IorCurve glass = IorCurve::abbe(n_d, v_d);
    // In double both hold to rounding (~1e-15); 1e-5 relative leaves room only for a wrong formula.
    EXPECT_NEAR(glass.index(kFraunhoferD), n_d, 1e-5);
    EXPECT_NEAR(abbe_number(glass), v_d, 1e-5 * v_d);
    EXPECT_NEAR(glass.at(587.56f), n_d, 1e-6);  // float argument and result
    // Normal dispersion: the index falls with wavelength over the whole range.
    for (float l = kLambdaMin; l < kLambdaMax; l += 1) ASSERT_GT(glass.at(l), glass.at(l + 1)) << l;
    EXPECT_TRUE(glass.dispersive());
    EXPECT_TRUE(glass.validate().ok()) << glass.validate().error().message;
  }
}

TEST(IorCurve, DiamondBySellmeier) {
  // Diamond (Peter 1923): n^2 = 1 + 4.3356 l^2 / (l^2 - 0.1060^2) + 0.3306 l^2 / (l^2 - 0.1750^2), l in um.
  // Handbooks give n_d = 2.417 and V_d = 55 (55.3 from this fit).
  const IorCurve diamond = IorCurve::sellmeier({4.3356, 0.3306, 0}, {0.1060 * 0.1060, 0.1750 * 0.1750, 0});
  EXPECT_NEAR(diamond.at(587.56f), 2.417, 1e-3);
  EXPECT_NEAR(abbe_number(diamond), 55, 1);
  EXPECT_TRUE(diamond.validate().ok());
  // Its Abbe approximation agrees within the two-term Cauchy's shape error (a few 1e-3 at the range ends).
  const IorCurve approx = IorCurve::abbe(diamond.index(kFraunhoferD), abbe_number(diamond));
  for (float l = 400; l <= 700; l += 50) EXPECT_NEAR(approx.at(l), diamond.at(l), 3e-3) << l;
}

TEST(IorCurve, CauchyAndConstant) {
  const IorCurve c = IorCurve::cauchy(1.5046, 0.00420);  // BK7-like two-term Cauchy, B in um^2
  EXPECT_NEAR(c.at(500), 1.5046 + 0.00420 / 0.25, 1e-6);
  const IorCurve c3 = IorCurve::cauchy(1.5, 0.004, 0.0001);
  EXPECT_NEAR(c3.at(400), 1.5 + 0.004 / 0.16 + 0.0001 / 0.0256, 1e-6);
  EXPECT_TRUE(c3.dispersive());
  const IorCurve k = IorCurve::constant(1.33);
  EXPECT_FLOAT_EQ(k.at(400), 1.33f);
  EXPECT_FLOAT_EQ(k.at(800), 1.33f);
  EXPECT_FALSE(k.dispersive());
  EXPECT_FALSE(IorCurve::cauchy(1.4, 0).dispersive());
  EXPECT_FALSE(IorCurve::sellmeier({1.2, 0, 0}, {0, 0, 0}).dispersive());  // n^2 = 2.2 everywhere
  EXPECT_TRUE(std::isinf(abbe_number(k)));
  EXPECT_FLOAT_EQ(IorCurve().at(550), 1.5f);
}

TEST(IorCurve, ValidationRejectsUnusableCurves) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  struct Case {
    const char *what;
    IorCurve curve;
  };
  const Case bad[] = {
      {"index below 1", IorCurve::constant(0.9)},
      {"index exactly 1", IorCurve::constant(1.0)},
      {"non-finite constant", IorCurve::constant(nan)},
      {"zero Abbe number", IorCurve::abbe(1.5, 0)},
      {"negative Abbe number", IorCurve::abbe(1.5, -30)},
      {"n_d not above 1", IorCurve::abbe(1.0, 40)},
      {"Cauchy falling below 1 in the red", IorCurve::cauchy(0.95, 0.02)},
      {"non-finite Cauchy term", IorCurve::cauchy(1.5, std::numeric_limits<double>::infinity())},
      {"Sellmeier pole at 500 nm", IorCurve::sellmeier({1.0, 0.2, 0}, {0.006, 0.25, 0})},
      {"Sellmeier with negative n^2", IorCurve::sellmeier({-3, 0, 0}, {0.01, 0, 0})},
  };
  for (const Case &c : bad) {
    const Status s = c.curve.validate();
    ASSERT_FALSE(s.ok()) << c.what;
    EXPECT_FALSE(s.error().message.empty()) << c.what;
  }
  EXPECT_NE(IorCurve::sellmeier({1.0, 0.2, 0}, {0.006, 0.25, 0}).validate().error().message.find("500"),
            std::string::npos);
}

}  // namespace ior_curve_test
}  // namespace nimbus
