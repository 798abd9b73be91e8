// Spectral building blocks for dispersion: the CIE 1931 colour matching functions, the weight that turns
// a radiance sample at one wavelength into linear Rec.709 RGB, pbrt-v4's visible-wavelength sampler and
// Jakob & Hanika's (2019) sigmoid-polynomial spectra. A path that turns monochromatic samples lambda from
// sample_visible_wavelength and adds S(lambda) * spectral_rgb_weight(lambda) /
// visible_wavelength_pdf(lambda).
#pragma once

#include <cmath>

#include <nimbus/cpp/math.hpp>

namespace nimbus {

// The visible range (nm) over which spectra are sampled and integrated.
inline constexpr float kLambdaMin = 360.0f;
inline constexpr float kLambdaMax = 830.0f;

namespace detail {

// One lobe of the fit: a Gaussian of height `height` at mu with different widths on either side, given as
// inverse standard deviations (nm^-1) as the paper's listing has them.
inline float cmf_lobe(float lambda, float height, float mu, float inv_sigma_below, float inv_sigma_above) {
  const float t = (lambda - mu) * (lambda < mu ? inv_sigma_below : inv_sigma_above);
  return height * std::exp(-0.5f * t * t);
}

}  // namespace detail

// CIE 1931 2-degree (x-bar, y-bar, z-bar) at lambda (nm): Wyman, Sloan & Shirley 2013, JCGT 2(2), multi-lobe.
inline Vec3f cie_xyz(float lambda) {
  using detail::cmf_lobe;
  const float x = cmf_lobe(lambda, 0.362f, 442.0f, 0.0624f, 0.0374f) +
                  cmf_lobe(lambda, 1.056f, 599.8f, 0.0264f, 0.0323f) -
                  cmf_lobe(lambda, 0.065f, 501.1f, 0.0490f, 0.0382f);
  const float y =
      cmf_lobe(lambda, 0.821f, 568.8f, 0.0213f, 0.0247f) + cmf_lobe(lambda, 0.286f, 530.9f, 0.0613f, 0.0322f);
  const float z =
      cmf_lobe(lambda, 1.217f, 437.0f, 0.0845f, 0.0278f) + cmf_lobe(lambda, 0.681f, 459.0f, 0.0385f, 0.0725f);
  return {x, y, z};
}

// CIE XYZ to linear Rec.709 / sRGB primaries with the D65 white (IEC 61966-2-1, Lindbloom's digits).
constexpr Vec3f xyz_to_linear_srgb(const Vec3f &c) {
  return {3.2404542f * c.x - 1.5371385f * c.y - 0.4985314f * c.z,
          -0.9692660f * c.x + 1.8760108f * c.y + 0.0415560f * c.z,
          0.0556434f * c.x - 0.2040259f * c.y + 1.0572252f * c.z};
}

// 1 / (the RGB of the equal-energy spectrum 1 over [kLambdaMin, kLambdaMax]): the fit's lobes integrated in
// closed form (erf) in double. Folding it into the weight makes the constant spectrum 1 exactly RGB
// (1, 1, 1), so that a white reflectance stays white; tests check it against numerical integration.
inline constexpr Vec3f kEqualEnergyRgbScale{7.803876089e-03f, 9.838843858e-03f, 1.029988680e-02f};

// The RGB that a unit of radiance at lambda contributes: for any spectrum S, the integral of
// S(lambda) * spectral_rgb_weight(lambda) over the visible range is S's RGB, and 1's is (1, 1, 1).
inline Vec3f spectral_rgb_weight(float lambda) {
  if (!(lambda >= kLambdaMin && lambda <= kLambdaMax)) return Vec3f(0);
  return xyz_to_linear_srgb(cie_xyz(lambda)) * kEqualEnergyRgbScale;
}

// pbrt-v4's SampleVisibleWavelengths: density proportional to 1 / cosh^2(a (lambda - 538 nm)),
// a = 0.0072 / nm, restricted to the visible range. It follows the sum of the matching functions closely,
// so every wavelength the eye sees is sampled and the RGB estimator's variance stays low.
namespace detail {
inline constexpr float kWavelengthSharpness = 0.0072f;  // a, 1/nm
inline constexpr float kWavelengthCentre = 538.0f;      // nm
// tanh(a (kLambdaMin - 538)) and tanh(a (kLambdaMax - 538)), in double, rounded (checked by a test).
inline constexpr float kWavelengthTanhMin = -0.856910625470f;
inline constexpr float kWavelengthTanhMax = 0.970591346940f;
// a / (tanh_max - tanh_min): the density's exact normalisation over the range.
inline constexpr float kWavelengthPdfScale = 3.939804229324e-03f;
}  // namespace detail

// A wavelength (nm) in [kLambdaMin, kLambdaMax] from u in [0, 1), by inverting the cdf
// (tanh(a (lambda - 538)) - tanh_min) / (tanh_max - tanh_min).
inline float sample_visible_wavelength(float u) {
  using namespace detail;
  const float t = kWavelengthTanhMin + u * (kWavelengthTanhMax - kWavelengthTanhMin);
  const float lambda = kWavelengthCentre + std::atanh(t) / kWavelengthSharpness;
  return clamp(lambda, kLambdaMin, kLambdaMax);
}

inline float visible_wavelength_pdf(float lambda) {
  using namespace detail;
  if (!(lambda >= kLambdaMin && lambda <= kLambdaMax)) return 0;
  return kWavelengthPdfScale / sqr(std::cosh(kWavelengthSharpness * (lambda - kWavelengthCentre)));
}

// Jakob & Hanika 2019, "A Low-Dimensional Function Space for Efficient Spectral Upsampling": a smooth
// spectrum in (0, 1) with at most one extremum, s(x) = 1/2 + x / (2 sqrt(1 + x^2)) of the quadratic
// x = c0 t^2 + c1 t + c2 in the normalised wavelength t = (lambda - kLambdaMin) / (kLambdaMax - kLambdaMin).
// Taking t in [0, 1] instead of nanometres keeps the three coefficients of similar size, which the fit's
// linear systems need. c2 = +-infinity gives the constants 1 and 0.
struct SigmoidSpectrum {
  float c0 = 0, c1 = 0, c2 = 0;

  static constexpr float normalized_wavelength(float lambda) {
    return (lambda - kLambdaMin) * (1.0f / (kLambdaMax - kLambdaMin));
  }
  // Past |x| = 1e8 the sigmoid is within 1e-17 of 0 or 1 and x * x could overflow, so it is 0 or 1.
  static float sigmoid(float x) {
    if (std::abs(x) > 1e8f) return x > 0 ? 1.0f : 0.0f;
    return 0.5f + x / (2.0f * std::sqrt(1.0f + x * x));
  }
  // The x at which sigmoid(x) == s, for s in [0, 1] (+-infinity at the ends): the constant spectrum s
  // is SigmoidSpectrum{0, 0, sigmoid_inverse(s)}.
  static float sigmoid_inverse(float s) {
    if (s <= 0) return -kInfinity;
    if (s >= 1) return kInfinity;
    return (s - 0.5f) / std::sqrt(s * (1.0f - s));
  }

  float polynomial(float lambda) const {
    const float t = normalized_wavelength(lambda);
    return (c0 * t + c1) * t + c2;
  }
  float operator()(float lambda) const { return sigmoid(polynomial(lambda)); }
};

}  // namespace nimbus
