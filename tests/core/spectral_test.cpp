// nimbus/cpp/spectral.hpp: the CIE fit against the tabulated CIE 1931 observer, the RGB weight (white is
// (1, 1, 1)), the Monte Carlo estimator of a spectrum's RGB through the visible-wavelength sampler, the
// sampler itself (chi-square against its pdf), and the sigmoid spectrum's closed forms.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <random>
#include <vector>

#include <nimbus/cpp/spectral.hpp>

namespace nimbus {
namespace spectral_test {

// Composite Simpson's rule of f over [a, b] in n (even) steps, in double. The integrands are smooth
// Gaussians and sigmoids with features ~10 nm wide, so 0.1 nm steps leave errors far below 1e-8.
double simpson(const std::function<double(double)> &f, double a, double b, int n) {
  const double h = (b - a) / n;
  double sum = f(a) + f(b);
  for (int k = 1; k < n; ++k) sum += (k % 2 == 1 ? 4 : 2) * f(a + k * h);
  return sum * h / 3;
}
constexpr int kSteps = 4700;  // 0.1 nm over the visible range

// The spectrum's RGB, by numerical integration of S * spectral_rgb_weight over [a, b] (where S is smooth).
Vec3f integrate_rgb(const std::function<double(double)> &s, double a = kLambdaMin, double b = kLambdaMax) {
  Vec3f rgb;
  for (int c = 0; c < 3; ++c)
    rgb[c] = float(simpson([&](double l) { return s(l) * spectral_rgb_weight(float(l))[c]; }, a, b, kSteps));
  return rgb;
}

double cmf_integral(int channel) {
  return simpson([&](double l) { return cie_xyz(float(l))[channel]; }, kLambdaMin, kLambdaMax, kSteps);
}

// Uniform float in [0, 1) from 24 random bits: the same sequence on every platform.
struct Uniform {
  std::mt19937_64 rng;
  explicit Uniform(uint64_t seed) : rng(seed) {}
  float operator()() { return float(rng() >> 40) * 0x1p-24f; }
};

TEST(CieFit, LuminanceIntegralIsTheTabulatedOne) {
  // The CIE 1931 table's y-bar sums to 106.857 over 360-830 nm at 1 nm. The fit's is 106.946: its lobes
  // err by ~0.1% overall (the paper's stated accuracy is of that order). A wrong width or height of any
  // lobe moves the integral by several units (the smallest lobe holds ~17), so 0.15 catches it.
  EXPECT_NEAR(cmf_integral(1), 106.857, 0.15);
}

TEST(CieFit, EqualEnergyIsAchromatic) {
  // The CIE observer is normalised so that X = Y = Z for the equal-energy spectrum: chromaticity
  // (1/3, 1/3). The fit gives (0.33295, 0.33367); 1.5e-3 is its error plus margin, well below the
  // 0.01 that one mis-typed lobe height would shift it by.
  const double x = cmf_integral(0), y = cmf_integral(1), z = cmf_integral(2);
  EXPECT_NEAR(x / (x + y + z), 1.0 / 3, 1.5e-3);
  EXPECT_NEAR(y / (x + y + z), 1.0 / 3, 1.5e-3);
}

TEST(CieFit, LuminancePeaksNear555) {
  // y-bar peaks at 555 nm with value 1 in the table; the fit's peak is at 554.1 nm, 0.998.
  float best = 0, best_lambda = 0;
  for (float l = 500; l <= 600; l += 0.1f)
    if (cie_xyz(l).y > best) best = cie_xyz(l).y, best_lambda = l;
  EXPECT_GE(best_lambda, 553.0f);
  EXPECT_LE(best_lambda, 557.0f);
  EXPECT_NEAR(best, 1.0f, 0.01f);
}

TEST(SpectralRgbWeight, ConstantSpectrumIsWhite) {
  // The scale is the closed form (erf) of the same integral, rounded to float: the 0.1 nm Simpson rule
  // agrees with it to ~1e-6, far inside 1e-4.
  const Vec3f white = integrate_rgb([](double) { return 1.0; });
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(white[c], 1.0f, 1e-4f) << "channel " << c;
  // Unscaled, the equal-energy spectrum is pinkish in Rec.709 (R 128, G 102, B 97): the scale matters.
  EXPECT_GT(1 / kEqualEnergyRgbScale.x, 1 / kEqualEnergyRgbScale.z * 1.2f);
  EXPECT_EQ(spectral_rgb_weight(kLambdaMin - 1), Vec3f(0));
  EXPECT_EQ(spectral_rgb_weight(kLambdaMax + 1), Vec3f(0));
}

TEST(SpectralRgbWeight, SrgbMatrixMapsD65WhiteToOne) {
  // D65's XYZ (Y = 1) is (0.95047, 1, 1.08883): the matrix maps it to (1, 1, 1) to its 7 digits.
  const Vec3f white = xyz_to_linear_srgb({0.95047f, 1.0f, 1.08883f});
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(white[c], 1.0f, 1e-4f) << "channel " << c;
}

// Monte Carlo estimate of a spectrum's RGB, lambda ~ visible_wavelength_pdf, against the integral.
void expect_estimator_matches(const char *name, const std::function<double(double)> &s, const Vec3f &exact,
                              uint64_t seed) {
  constexpr int n = 1'000'000;
  Uniform u(seed);
  double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
  for (int i = 0; i < n; ++i) {
    const float lambda = sample_visible_wavelength(u());
    const Vec3f v = spectral_rgb_weight(lambda) * float(s(lambda) / visible_wavelength_pdf(lambda));
    for (int c = 0; c < 3; ++c) sum[c] += v[c], sum2[c] += double(v[c]) * v[c];
  }
  for (int c = 0; c < 3; ++c) {
    const double mean = sum[c] / n, variance = sum2[c] / n - mean * mean;
    const double sigma = std::sqrt(variance / n);  // standard error of the mean
    ASSERT_GT(sigma, 0) << name;
    // 4 sigma: a correct estimator fails one of the 9 channels with probability ~6e-4 (and a fixed seed
    // makes it reproducible); an unnormalised pdf or weight is off by percents, hundreds of sigma.
    EXPECT_NEAR(mean, exact[c], 4 * sigma) << name << " channel " << c << " sigma " << sigma;
  }
}

TEST(SpectralEstimator, MatchesTheIntegral) {
  auto one = [](double) { return 1.0; };
  expect_estimator_matches("constant", one, integrate_rgb(one), 1);
  // A narrow band: ~4% of the samples land in it. Its integral is over the band alone, where it is smooth.
  auto band = [](double l) { return l >= 500 && l < 510 ? 1.0 : 0.0; };
  expect_estimator_matches("band 500-510 nm", band, integrate_rgb(one, 500, 510), 2);
  const SigmoidSpectrum orange{-20.0f, 25.0f, -5.0f};
  auto sigmoid = [&](double l) { return orange(float(l)); };
  expect_estimator_matches("sigmoid", sigmoid, integrate_rgb(sigmoid), 3);
}

double wavelength_cdf(double lambda) {
  return simpson([](double l) { return visible_wavelength_pdf(float(l)); }, kLambdaMin, lambda, 2000);
}

TEST(VisibleWavelengths, PdfIntegratesToOneAndVanishesOutside) {
  EXPECT_NEAR(wavelength_cdf(kLambdaMax), 1.0, 1e-6);  // the constants' float rounding is ~1e-7
  EXPECT_EQ(visible_wavelength_pdf(kLambdaMin - 0.5f), 0.0f);
  EXPECT_EQ(visible_wavelength_pdf(kLambdaMax + 0.5f), 0.0f);
  // The constants are tanh at the ends and the normalisation they imply, in double.
  const double a = 0.0072, lo = std::tanh(a * (kLambdaMin - 538)), hi = std::tanh(a * (kLambdaMax - 538));
  EXPECT_NEAR(detail::kWavelengthTanhMin, lo, 1e-7);
  EXPECT_NEAR(detail::kWavelengthTanhMax, hi, 1e-7);
  EXPECT_NEAR(detail::kWavelengthPdfScale, a / (hi - lo), 1e-9);
}

TEST(VisibleWavelengths, SampleInvertsTheCdf) {
  // cdf(sample(u)) == u: float atanh near the ends moves lambda by ~1e-3 nm, the cdf by ~1e-6.
  for (int i = 0; i <= 100; ++i) {
    const float u = std::min(float(i) / 100, 0x1.fffffep-1f);
    const float lambda = sample_visible_wavelength(u);
    ASSERT_GE(lambda, kLambdaMin);
    ASSERT_LE(lambda, kLambdaMax);
    EXPECT_NEAR(wavelength_cdf(lambda), u, 1e-5) << "u " << u;
  }
}

TEST(VisibleWavelengths, HistogramMatchesPdf) {
  // 50 equal bins over the range, 10^6 samples; expected counts from the integrated pdf (each >= 2000).
  constexpr int bins = 50, n = 1'000'000;
  std::vector<double> observed(bins, 0);
  Uniform u(7);
  for (int i = 0; i < n; ++i) {
    const float t = (sample_visible_wavelength(u()) - kLambdaMin) / (kLambdaMax - kLambdaMin);
    ++observed[std::min(int(t * bins), bins - 1)];
  }
  double chi2 = 0, previous = 0;
  for (int b = 0; b < bins; ++b) {
    const double next = wavelength_cdf(kLambdaMin + (kLambdaMax - kLambdaMin) * (b + 1) / bins);
    const double expected = n * (next - previous);
    chi2 += (observed[b] - expected) * (observed[b] - expected) / expected;
    previous = next;
  }
  // The chi-square distribution with 49 degrees of freedom exceeds 94.6 with probability 1e-4.
  std::printf("wavelength sampler: chi2 = %.2f over 49 degrees of freedom (p = 1e-4 at 94.6)\n", chi2);
  EXPECT_LT(chi2, 94.6);
}

TEST(SigmoidSpectrum, ConstantsAndBounds) {
  for (float g : {0.01f, 0.2f, 0.5f, 0.77f, 0.99f}) {
    const SigmoidSpectrum s{0, 0, SigmoidSpectrum::sigmoid_inverse(g)};
    EXPECT_NEAR(s(400), g, 1e-6f);
    EXPECT_NEAR(s(700), g, 1e-6f);
  }
  EXPECT_EQ(SigmoidSpectrum::sigmoid(kInfinity), 1.0f);
  EXPECT_EQ(SigmoidSpectrum::sigmoid(-kInfinity), 0.0f);
  EXPECT_EQ(SigmoidSpectrum::sigmoid(1e30f), 1.0f);  // x * x would overflow
  // Coefficients in normalised wavelength: t = 0 at kLambdaMin, 1 at kLambdaMax.
  const SigmoidSpectrum linear{0, 2, -1};
  EXPECT_NEAR(linear.polynomial(kLambdaMin), -1.0f, 1e-6f);
  EXPECT_NEAR(linear.polynomial(kLambdaMax), 1.0f, 1e-6f);
  EXPECT_NEAR(linear(0.5f * (kLambdaMin + kLambdaMax)), 0.5f, 1e-6f);
  for (float l = 300; l <= 900; l += 10) {
    const float v = SigmoidSpectrum{50, -40, 3}(l);
    EXPECT_GE(v, 0.0f);
    EXPECT_LE(v, 1.0f);
  }
}

}  // namespace spectral_test
}  // namespace nimbus
