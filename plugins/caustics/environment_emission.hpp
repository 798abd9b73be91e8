// Photon emission directions of an environment map (solver spec 6.2): the emission weight of a direction
// is e(w) = max(0, L(w) - 2 mu), L the map's luminance and mu its mean over the sphere. A uniform map, and
// a sky whose peak is below twice its mean, emit nothing (path tracing renders their soft caustics
// better); a sun, a window or a lamp in an HDRI keeps nearly all its weight while the dim texels lose
// theirs. The weight is derived from the map alone, through the light's own emission sampler (host
// sample_emission), so any environment light plugin gets it.
//
// Directions are binned on an equal-area grid of the sphere (rows uniform in z = cos theta, columns
// uniform in phi), so every cell spans the same solid angle 4 pi / cells and a cell's emission
// probability over that solid angle is its direction density: sampling and the camera side's density
// (pdf) read the same table, as MIS needs. A cell's mean luminance comes from the light's own samples
// that fall in it (self-normalised importance sampling): a texel-sized sun, far smaller than a cell, is
// found by the samples the light sends towards it, where point samples of the cell would miss it.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <nimbus/cpp/alias_table.hpp>
#include <nimbus/cpp/math.hpp>

namespace nimbus::caustics {

class EnvironmentEmission {
 public:
  static constexpr uint32_t kColumns = 256, kRows = 128;  // cells of 4 pi / 32768 sr, ~1.4 degrees wide

  // The direction (towards the environment) at the equal-area coordinates (a, b) in [0, 1)^2.
  static Vec3f direction(float a, float b) {
    const float z = 1 - 2 * b, s = std::sqrt(std::max(0.0f, 1 - z * z)), phi = 2 * kPi * a;
    return Vec3f(s * std::cos(phi), s * std::sin(phi), z);
  }

  // sample(u0, u1) -> LightDirection: a direction of the light's own sampler for the pair (u0, u1),
  // with the luminance along it and its solid-angle pdf. `samples` pairs on a stratified grid.
  struct LightDirection {
    Vec3f dir;  // towards the environment
    float luminance = 0, pdf = 0;
  };
  template <class Sampler>
  void build(Sampler &&sample, uint32_t samples = 64 * kColumns * kRows) {
    // Per cell, the samples' sums of L / pdf and 1 / pdf: their ratio is the cell's mean luminance
    // (self-normalised importance sampling), whatever the share of samples the cell received.
    std::vector<double> lum(size_t(kColumns) * kRows, 0.0), area(lum.size(), 0.0);
    const uint32_t side = std::max(1u, uint32_t(std::sqrt(double(samples))));
    double total = 0;  // the integral of L over the sphere, times side^2
    for (uint32_t i = 0; i < side; ++i)
      for (uint32_t j = 0; j < side; ++j) {
        const LightDirection d = sample((float(i) + 0.5f) / float(side), (float(j) + 0.5f) / float(side));
        if (!(d.pdf > 0) || !std::isfinite(d.pdf) || !(d.luminance >= 0) || !std::isfinite(d.luminance))
          continue;
        const size_t c = cell_of(d.dir);
        lum[c] += double(d.luminance) / d.pdf, area[c] += 1.0 / d.pdf, total += double(d.luminance) / d.pdf;
      }
    // mu: the mean over the sphere. Cells no sample reached are those the light's sampler finds dim.
    const double mean = total / (double(side) * side * 4 * kPi), cell_sr = 4 * kPi / double(lum.size());
    double kept = 0;
    for (size_t c = 0; c < lum.size(); ++c) {
      lum[c] = area[c] > 0 ? std::max(0.0, lum[c] / area[c] - 2 * mean) : 0.0;
      kept += lum[c] * cell_sr;
    }
    table_ = AliasTable(lum);
    emitted_share_ = mean > 0 ? kept / (mean * 4 * kPi) : 0.0;
  }

  // Whether any direction emits photons.
  bool emits() const { return !table_.empty(); }
  // The share of the map's luminance (its integral over the sphere) that the emission weight keeps.
  double emitted_share() const { return emitted_share_; }

  struct Sample {
    Vec3f dir;      // towards the environment: the photon travels along -dir
    float pdf = 0;  // solid-angle density of dir
  };
  // u_cell picks the cell; (u_a, u_b) place the direction uniformly in it (uniform in solid angle).
  Sample sample(float u_cell, float u_a, float u_b) const {
    float pmf = 0;
    const int64_t i = table_.sample(u_cell, &pmf);
    if (i < 0 || !(pmf > 0)) return {};
    const uint32_t r = uint32_t(i) / kColumns, c = uint32_t(i) % kColumns;
    const float a = std::min((float(c) + u_a) / kColumns, 0x1.fffffep-1f);
    const float b = std::min((float(r) + u_b) / kRows, 0x1.fffffep-1f);
    return {direction(a, b), pmf * kCellsPerSteradian};
  }

  // Solid-angle density of sampling direction w (towards the environment): 0 where nothing is emitted.
  float pdf(const Vec3f &w) const {
    return table_.empty() ? 0.0f : table_.pmf(cell_of(w)) * kCellsPerSteradian;
  }

 private:
  static size_t cell_of(const Vec3f &w) {
    const float z = std::clamp(w.z, -1.0f, 1.0f);
    float phi = std::atan2(w.y, w.x);
    if (phi < 0) phi += 2 * kPi;
    const uint32_t c = std::min(uint32_t(phi / (2 * kPi) * kColumns), kColumns - 1);
    const uint32_t r = std::min(uint32_t((1 - z) / 2 * kRows), kRows - 1);
    return size_t(r) * kColumns + c;
  }

  static constexpr float kCellsPerSteradian = float(kColumns * kRows) / (4 * kPi);
  AliasTable table_;
  double emitted_share_ = 0;
};

}  // namespace nimbus::caustics
