// Precomputed RGB to spectrum uplift (Jakob & Hanika 2019, section 4): sigmoid coefficients fitted on a
// grid over the RGB cube and interpolated, so that a lookup costs a few loads instead of a fit.
#pragma once

#include <vector>

#include <nimbus/cpp/math.hpp>
#include <nimbus/cpp/spectral.hpp>
#include "core/spectral_uplift.hpp"

namespace nimbus {

// The grid follows the paper: for each choice of the brightest channel, res^3 nodes over (z = brightest
// value, x = next channel / z, y = the one after / z). All three axes place their nodes at
// smoothstep(k / (res - 1)), crowding them near 0 and 1, where the coefficients change fastest (saturated
// colours, black); the paper's uniform x and y left errors four times larger there. Each node is fitted
// from its neighbour's coefficients (continuation), which keeps every Newton start close. Immutable after
// construction: lookups from many threads need no locking.
class RgbUpliftTable {
 public:
  // 0.3 s to build on one core; lookups within 1e-3 of the colour wherever the model reaches it.
  static constexpr int kDefaultResolution = 48;

  explicit RgbUpliftTable(int resolution = kDefaultResolution);

  int resolution() const { return res_; }
  // The largest RGB error any cell's fit left (by the fit's quadrature): what the model could not reach.
  float max_cell_error() const { return max_cell_error_; }

  // The reflectance spectrum of rgb (channels clamped to [0, 1]) by trilinear interpolation of the
  // coefficients of the cell around it; greys (black and white included) are exact.
  SigmoidSpectrum lookup(Vec3f rgb) const;
  // Emission as fit_emission has it, the shape from the table.
  UpliftedEmission lookup_emission(Vec3f rgb) const;

 private:
  SigmoidSpectrum &cell(int channel, int z, int y, int x) {
    return coeffs_[((size_t(channel) * res_ + z) * res_ + y) * res_ + x];
  }
  const SigmoidSpectrum &cell(int channel, int z, int y, int x) const {
    return coeffs_[((size_t(channel) * res_ + z) * res_ + y) * res_ + x];
  }
  Vec3f cell_rgb(int channel, int z, int y, int x) const;
  bool needed(int z, int y, int x) const;
  void fit_channel(int channel);
  // The cell i of the nodes below v in [0, 1], and v's fraction f of the way to the next.
  void locate(float v, int &i, float &f) const;

  int res_;
  std::vector<float> nodes_;             // res_ increasing values from 0 to 1, the same on every axis
  std::vector<SigmoidSpectrum> coeffs_;  // [brightest channel][z][y][x]
  float max_cell_error_ = 0;
};

// The table at the default resolution, built on first use (thread-safe) and kept for the process.
const RgbUpliftTable &srgb_uplift_table();

// The value at lambda (nm) of the smooth spectrum of linear rgb of any magnitude: its largest channel m
// times the bounded spectrum of rgb / m, so homogeneous (uplift(k rgb) = k uplift(rgb): a BSDF value
// albedo / pi gives uplift(albedo) / pi) and never above m (an albedo stays below 1 at every wavelength).
// Negative channels count as 0; greys are exact and never build the table; 0 outside the visible range.
float uplift(const Vec3f &rgb, float lambda);

}  // namespace nimbus
