#include "core/rgb_uplift_table.hpp"

#include <algorithm>
#include <cmath>

namespace nimbus {

namespace {

constexpr int kIterations = 30;  // per cell; a neighbour's coefficients are usually 2 or 3 steps away
// Above this RGB error (the most a colour out of the model's reach needs) a continued fit went astray in
// the dark unreachable corner; fit_reflectance's continuation from grey is tried instead.
constexpr float kRefitError = 1e-3f;

SigmoidSpectrum lerp(const SigmoidSpectrum &a, const SigmoidSpectrum &b, float t) {
  return {a.c0 + (b.c0 - a.c0) * t, a.c1 + (b.c1 - a.c1) * t, a.c2 + (b.c2 - a.c2) * t};
}
SigmoidSpectrum negated(const SigmoidSpectrum &s) { return {-s.c0, -s.c1, -s.c2}; }

}  // namespace

RgbUpliftTable::RgbUpliftTable(int resolution)
    : res_(std::max(resolution, 3)), nodes_(res_), coeffs_(3 * size_t(res_) * res_ * res_) {
  for (int k = 0; k < res_; ++k) {
    const float t = float(k) / float(res_ - 1);
    nodes_[k] = t * t * (3 - 2 * t);  // smoothstep
  }
  for (int channel = 0; channel < 3; ++channel) fit_channel(channel);
}

Vec3f RgbUpliftTable::cell_rgb(int channel, int z, int y, int x) const {
  Vec3f rgb;
  rgb[channel] = nodes_[z];
  rgb[(channel + 1) % 3] = nodes_[z] * nodes_[x];
  rgb[(channel + 2) % 3] = nodes_[z] * nodes_[y];
  return rgb;
}

// Lookups of colours whose channels sum to more than 3/2 go through their complement, so a cell is needed
// only when some grid cube it is a corner of reaches below that sum; its lowest corner tells.
bool RgbUpliftTable::needed(int z, int y, int x) const {
  const float lowest =
      nodes_[std::max(z - 1, 0)] * (1 + nodes_[std::max(x - 1, 0)] + nodes_[std::max(y - 1, 0)]);
  return lowest <= 1.5f;
}

void RgbUpliftTable::fit_channel(int channel) {
  auto fit_cell = [&](int z, int y, int x, const SigmoidSpectrum &from) {
    const Vec3f rgb = cell_rgb(channel, z, y, x);
    ReflectanceFit fit = rgb.x == rgb.y && rgb.y == rgb.z
                             ? ReflectanceFit{constant_sigmoid_spectrum(rgb.x), 0}
                             : refine_reflectance_fit(rgb, from, kIterations);
    if (fit.error > kRefitError) {
      const ReflectanceFit fresh = fit_reflectance_with_error(rgb);
      if (fresh.error < fit.error) fit = fresh;
    }
    max_cell_error_ = std::max(max_cell_error_, fit.error);
    cell(channel, z, y, x) = fit.spectrum;
  };
  // The middle slice first, where the model reaches every colour, walked in a serpentine so that each
  // cell starts from the one just fitted; then every column, up and down in z from that slice. The black
  // slice repeats the darkest fitted one: every colour there is black, and lookups between the two
  // slices are within nodes_[1] of it.
  const int start = res_ / 2;
  SigmoidSpectrum previous = constant_sigmoid_spectrum(nodes_[start]);
  for (int y = 0; y < res_; ++y)
    for (int step = 0; step < res_; ++step) {
      const int x = y % 2 == 0 ? step : res_ - 1 - step;
      fit_cell(start, y, x, previous);
      previous = cell(channel, start, y, x);
    }
  for (int y = 0; y < res_; ++y)
    for (int x = 0; x < res_; ++x) {
      for (int z = start + 1; z < res_ && needed(z, y, x); ++z) fit_cell(z, y, x, cell(channel, z - 1, y, x));
      for (int z = start - 1; z >= 1; --z) fit_cell(z, y, x, cell(channel, z + 1, y, x));
      cell(channel, 0, y, x) = cell(channel, 1, y, x);
    }
}

void RgbUpliftTable::locate(float v, int &i, float &f) const {
  i = std::clamp(int(std::upper_bound(nodes_.begin(), nodes_.end(), v) - nodes_.begin()) - 1, 0, res_ - 2);
  f = clamp((v - nodes_[i]) / (nodes_[i + 1] - nodes_[i]), 0.0f, 1.0f);
}

SigmoidSpectrum RgbUpliftTable::lookup(Vec3f rgb) const {
  for (int i = 0; i < 3; ++i) rgb[i] = std::isnan(rgb[i]) ? 0.0f : clamp(rgb[i], 0.0f, 1.0f);
  if (rgb.x == rgb.y && rgb.y == rgb.z) return constant_sigmoid_spectrum(rgb.x);
  // 1 - s(x) = s(-x) and white is (1, 1, 1), so the spectrum of 1 - rgb is 1 minus rgb's: bright colours
  // use the cells of their (dark) complement, where smoothstep crowds the nodes.
  if (rgb.x + rgb.y + rgb.z > 1.5f) return negated(lookup(Vec3f(1) - rgb));
  const int channel = rgb.x >= rgb.y ? (rgb.x >= rgb.z ? 0 : 2) : (rgb.y >= rgb.z ? 1 : 2);
  const float z = rgb[channel];  // > 0: not all channels are equal
  int xi, yi, zi;
  float fx, fy, fz;
  locate(rgb[(channel + 1) % 3] / z, xi, fx);
  locate(rgb[(channel + 2) % 3] / z, yi, fy);
  locate(z, zi, fz);
  auto along_x = [&](int dz, int dy) {
    return lerp(cell(channel, zi + dz, yi + dy, xi), cell(channel, zi + dz, yi + dy, xi + 1), fx);
  };
  return lerp(lerp(along_x(0, 0), along_x(0, 1), fy), lerp(along_x(1, 0), along_x(1, 1), fy), fz);
}

UpliftedEmission RgbUpliftTable::lookup_emission(Vec3f rgb) const {
  rgb = max(rgb, Vec3f(0));
  const float scale = 2 * max_component(rgb);
  if (!(scale > 0) || !std::isfinite(scale)) return {constant_sigmoid_spectrum(0), 0};
  return {lookup(rgb / scale), scale};
}

const RgbUpliftTable &srgb_uplift_table() {
  static const RgbUpliftTable table;
  return table;
}

float uplift(const Vec3f &rgb, float lambda) {
  if (!(lambda >= kLambdaMin && lambda <= kLambdaMax)) return 0;
  // Greys are exact without the table.
  if (rgb.x == rgb.y && rgb.y == rgb.z) return std::isfinite(rgb.x) ? std::max(rgb.x, 0.0f) : 0.0f;
  // The largest channel m times the bounded spectrum of rgb / m, which lies in [0, 1]: homogeneous, and
  // never above m at any wavelength, so an albedo below 1 stays below 1 at every wavelength (a factor of
  // 2 m, as for emission, would let a saturated albedo reflect more than it receives at some).
  const Vec3f c = max(rgb, Vec3f(0));
  const float m = max_component(c);
  if (!(m > 0) || !std::isfinite(m)) return 0;
  return m * srgb_uplift_table().lookup(c / m)(lambda);
}

}  // namespace nimbus
