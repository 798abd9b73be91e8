// RGB to spectrum (Jakob & Hanika 2019): the sigmoid-polynomial spectrum whose RGB, through the
// matching functions and spectral_rgb_weight, is a given colour. A dispersive path that meets an RGB
// texture or light turns the colour into a value at its wavelength with these; rgb_uplift_table.hpp
// precomputes them for lookups.
#pragma once

#include <nimbus/cpp/math.hpp>
#include <nimbus/cpp/spectral.hpp>

namespace nimbus {

// The |c2| of the constant spectra 0 and 1: sigmoid(+-1e4) rounds to exactly 1 and 0 in float (the exact
// sigmoid is within 1 / (4 c2^2) = 2.5e-9 of them), and unlike infinity it can be interpolated.
inline constexpr float kSigmoidSaturated = 1e4f;

// The constant spectrum g in [0, 1] (exact: sigmoid(c2) == g, 0 and 1 through kSigmoidSaturated).
SigmoidSpectrum constant_sigmoid_spectrum(float g);

// The RGB of a reflectance spectrum by the fit's own quadrature (Simpson's rule over the visible range,
// normalised so that the constant 1 is exactly (1, 1, 1)).
Vec3f reflectance_rgb(const SigmoidSpectrum &s);

struct ReflectanceFit {
  SigmoidSpectrum spectrum;
  float error = 0;  // the largest |RGB channel - target| left (0 when the target is reachable)
};

// Levenberg-Marquardt from `start` towards the spectrum of rgb (in [0, 1]^3): what the table does from its
// neighbouring cell. At most `max_iterations` steps; stops once every channel is within 1e-6, or when the
// error no longer falls (a colour out of the model's reach: dark saturated ones and their complements).
ReflectanceFit refine_reflectance_fit(const Vec3f &rgb, const SigmoidSpectrum &start, int max_iterations);

// The reflectance spectrum of rgb, each channel clamped to [0, 1]: closed form for greys (black and white
// are the constants 0 and 1), otherwise a fit continued from the grey of the same mean towards rgb.
ReflectanceFit fit_reflectance_with_error(Vec3f rgb);
inline SigmoidSpectrum fit_reflectance(const Vec3f &rgb) { return fit_reflectance_with_error(rgb).spectrum; }

// Unbounded RGB (emission): value(lambda) = scale * shape(lambda) with scale = 2 max(rgb), so that the
// shape fits rgb / scale, whose largest channel is 1/2: a mid-range reflectance the model fits well
// (pbrt-v4's RGBUnboundedSpectrum).
struct UpliftedEmission {
  SigmoidSpectrum shape;
  float scale = 0;
  float operator()(float lambda) const { return scale * shape(lambda); }
};

// rgb's negative channels count as 0.
UpliftedEmission fit_emission(Vec3f rgb);

}  // namespace nimbus
