// The Preetham, Shirley & Smits (1999) sky of lights/sky_model.cpp against "A Practical Analytic Model for
// Daylight", recomputed here in double precision from the paper's Appendix A and nothing of the host: the
// zenith luminance Yz (kcd/m^2) and chromaticity xz, yz of A.2, the Perez distribution
// F(theta, gamma) = (1 + A exp(B / cos theta)) (1 + C exp(D gamma) + E cos^2 gamma) with the coefficients
// of A.1, each quantity Q = Qz F(theta, gamma) / F(0, theta_s), and the conversion sky_model.hpp states:
// luminance in cd/m^2 over 683 lm/W, CIE XYZ to linear Rec.709 by the IEC 61966-2-1 matrix.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "lights/sky_model.hpp"

namespace nimbus {
namespace sky_model_test {

constexpr double kPi = 3.14159265358979323846;

// A.1: [A B C D E] = M [T 1] for luminance Y and chromaticities x, y.
using PerezMatrix = std::array<std::array<double, 2>, 5>;
constexpr PerezMatrix kPerezY{
    {{0.1787, -1.4630}, {-0.3554, 0.4275}, {-0.0227, 5.3251}, {0.1206, -2.5771}, {-0.0670, 0.3703}}};
constexpr PerezMatrix kPerezX{
    {{-0.0193, -0.2592}, {-0.0665, 0.0008}, {-0.0004, 0.2125}, {-0.0641, -0.8989}, {-0.0033, 0.0452}}};
constexpr PerezMatrix kPerezYc{
    {{-0.0167, -0.2608}, {-0.0950, 0.0092}, {-0.0079, 0.2102}, {-0.0441, -1.6537}, {-0.0109, 0.0529}}};

// A.2: xz, yz = [T^2 T 1] M [theta_s^3 theta_s^2 theta_s 1]^T.
using ZenithMatrix = std::array<std::array<double, 4>, 3>;
constexpr ZenithMatrix kZenithX{{{0.00166, -0.00375, 0.00209, 0},
                                 {-0.02903, 0.06377, -0.03202, 0.00394},
                                 {0.11693, -0.21196, 0.06052, 0.25886}}};
constexpr ZenithMatrix kZenithY{{{0.00275, -0.00610, 0.00317, 0},
                                 {-0.04214, 0.08970, -0.04153, 0.00516},
                                 {0.15346, -0.26756, 0.06670, 0.26688}}};

double perez(const PerezMatrix &m, double T, double theta, double gamma) {
  double c[5];
  for (int i = 0; i < 5; ++i) c[i] = m[i][0] * T + m[i][1];
  return (1 + c[0] * std::exp(c[1] / std::cos(theta))) *
         (1 + c[2] * std::exp(c[3] * gamma) + c[4] * std::cos(gamma) * std::cos(gamma));
}

double zenith_chromaticity(const ZenithMatrix &m, double T, double ts) {
  const double t[3] = {T * T, T, 1}, s[4] = {ts * ts * ts, ts * ts, ts, 1};
  double sum = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j) sum += t[i] * m[i][j] * s[j];
  return sum;
}

struct XyY {
  double x, y, Y;  // Y in kcd/m^2
};

XyY paper_sky(double T, double theta_s, double theta, double gamma) {
  const double chi = (4.0 / 9.0 - T / 120.0) * (kPi - 2 * theta_s);
  const double Yz = (4.0453 * T - 4.9710) * std::tan(chi) - 0.2155 * T + 2.4192;
  return {zenith_chromaticity(kZenithX, T, theta_s) * perez(kPerezX, T, theta, gamma) /
              perez(kPerezX, T, 0, theta_s),
          zenith_chromaticity(kZenithY, T, theta_s) * perez(kPerezYc, T, theta, gamma) /
              perez(kPerezYc, T, 0, theta_s),
          Yz * perez(kPerezY, T, theta, gamma) / perez(kPerezY, T, 0, theta_s)};
}

// The radiance sky_model.hpp documents for a paper value: W/(m^2 sr) per linear Rec.709 channel.
std::array<double, 3> expected_rgb(const XyY &v) {
  const double Y = v.Y * 1000 / 683, X = v.x / v.y * Y, Z = (1 - v.x - v.y) / v.y * Y;
  return {std::max(0.0, 3.2406 * X - 1.5372 * Y - 0.4986 * Z),
          std::max(0.0, -0.9689 * X + 1.8758 * Y + 0.0415 * Z),
          std::max(0.0, 0.0557 * X - 0.2040 * Y + 1.0570 * Z)};
}

Vec3f from_angles(double theta, double phi) {
  return {float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)),
          float(std::cos(theta))};
}

constexpr double kTurbidities[] = {2, 3, 4.5, 6, 10};
constexpr double kSunZenithDeg[] = {0, 20, 45, 70, 85};

// Per channel, relative to the brightest: the host evaluates in single precision, within 3e-6 of these
// values away from the sun's own direction (there its float acos of gamma is off by up to
// sqrt(float epsilon), so no view direction below coincides with the sun); the tolerance is 2e-5. A change
// of one in the last printed digit of Yz's, the zenith chromaticities' or the Perez coefficients fails it
// (all but the largest, C of Y at 5.3251).
void expect_matches_paper(double T, double theta_s_deg, double theta_deg, double phi_deg, double tolerance,
                          double *worst) {
  const double ts = theta_s_deg * kPi / 180, theta = theta_deg * kPi / 180, phi = phi_deg * kPi / 180;
  const Vec3f to_sun = from_angles(ts, 0), dir = from_angles(theta, phi);
  // gamma from the directions the host is given, in double.
  const double cos_gamma = double(to_sun.x) * dir.x + double(to_sun.y) * dir.y + double(to_sun.z) * dir.z;
  const double gamma = std::acos(std::clamp(cos_gamma, -1.0, 1.0));
  const std::array<double, 3> want = expected_rgb(paper_sky(T, ts, std::acos(double(dir.z)), gamma));
  const Rgb got = preetham_sky_radiance(dir, to_sun, float(T));
  const double scale = std::max({want[0], want[1], want[2]});
  for (int c = 0; c < 3; ++c) {
    const double err = std::abs(got[c] - want[c]) / scale;
    *worst = std::max(*worst, err);
    EXPECT_LE(err, tolerance) << "T " << T << ", sun at " << theta_s_deg
                              << " deg from the zenith, view theta " << theta_deg << " phi " << phi_deg
                              << ", channel " << c << ": " << got[c] << " vs " << want[c];
  }
}

// At the zenith F(theta, gamma) / F(0, theta_s) is 1: the radiance is A.2's Yz, xz, yz alone.
TEST(PreethamSky, ZenithIsAppendixA2) {
  double worst = 0;
  for (double T : kTurbidities)
    for (double ts : kSunZenithDeg) expect_matches_paper(T, ts, 0, 0, 2e-5, &worst);
  RecordProperty("worst_relative_error", std::to_string(worst));
}

// Everywhere above the horizon: the zenith values distributed by A.1's Perez coefficients, towards the
// sun, across from it and near the horizon (view zenith angles that are none of the sun's).
TEST(PreethamSky, SkyIsPerezDistributedWithAppendixA1) {
  double worst = 0;
  for (double T : kTurbidities)
    for (double ts : kSunZenithDeg)
      for (double theta : {10.0, 40.0, 65.0, 88.0})
        for (double phi : {0.0, 60.0, 135.0, 180.0}) expect_matches_paper(T, ts, theta, phi, 2e-5, &worst);
  RecordProperty("worst_relative_error", std::to_string(worst));
}

}  // namespace sky_model_test
}  // namespace nimbus
