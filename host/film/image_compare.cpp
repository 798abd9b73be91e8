#include "film/image_compare.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>

#include "core/image_io.hpp"
#include "film/atomic_file.hpp"
#include "film/png_write.hpp"

namespace nimbus {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// matplotlib's viridis (CC0) sampled at 0, 0.1, ..., 1, in sRGB; linear interpolation between these
// stays within a few 8-bit steps of the full 256-entry table.
constexpr std::array<std::array<float, 3>, 11> kViridis = {{
    {0.267004f, 0.004874f, 0.329415f},
    {0.282623f, 0.140926f, 0.457517f},
    {0.253935f, 0.265254f, 0.529983f},
    {0.206756f, 0.371758f, 0.553117f},
    {0.163625f, 0.471133f, 0.558148f},
    {0.127568f, 0.566949f, 0.550556f},
    {0.134692f, 0.658636f, 0.517649f},
    {0.266941f, 0.748751f, 0.440573f},
    {0.477504f, 0.821444f, 0.318195f},
    {0.741388f, 0.873449f, 0.149561f},
    {0.993248f, 0.906157f, 0.143936f},
}};

std::array<uint8_t, 3> viridis(double t) {
  t = std::clamp(t, 0.0, 1.0) * double(kViridis.size() - 1);
  const size_t i = std::min(static_cast<size_t>(t), kViridis.size() - 2);
  const double f = t - double(i);
  std::array<uint8_t, 3> rgb{};
  for (int c = 0; c < 3; ++c) {
    const double v = kViridis[i][c] + f * (kViridis[i + 1][c] - kViridis[i][c]);
    rgb[c] = static_cast<uint8_t>(std::lround(v * 255.0));
  }
  return rgb;
}

double luminance(const float *p, size_t channels) {
  if (channels >= 3) return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
  double sum = 0;
  for (size_t c = 0; c < channels; ++c) sum += p[c];
  return sum / double(channels);
}

bool finite_pixel(const float *p, size_t channels) {
  for (size_t c = 0; c < channels; ++c)
    if (!std::isfinite(p[c])) return false;
  return true;
}

double relative_squared(double t, double r) { return (t - r) * (t - r) / (r * r + kCompareEpsilon); }

}  // namespace

Expected<ImageMetrics> compare_images(const ImageLayer &test, const ImageLayer &ref, uint32_t width,
                                      uint32_t height) {
  const size_t channels = test.channel_names.size();
  if (channels == 0 || channels != ref.channel_names.size()) {
    return Error{"the layers have different channel counts (" + std::to_string(channels) + " in TEST, " +
                 std::to_string(ref.channel_names.size()) + " in REF)"};
  }
  const size_t pixels = size_t(width) * height;
  if (test.data.size() != pixels * channels || ref.data.size() != pixels * channels)
    return Error{"the layer data does not match the image size"};

  ImageMetrics m;
  m.pixels = pixels;
  // Sums in double, one pass: the images are small next to double's 53 bits.
  double squared = 0, relative = 0, absolute = 0, relative_y = 0;
  for (size_t p = 0; p < pixels; ++p) {
    const float *t = &test.data[p * channels];
    const float *r = &ref.data[p * channels];
    const bool t_ok = finite_pixel(t, channels), r_ok = finite_pixel(r, channels);
    m.nonfinite_test += !t_ok;
    m.nonfinite_reference += !r_ok;
    if (!t_ok || !r_ok) continue;
    ++m.compared_pixels;
    for (size_t c = 0; c < channels; ++c) {
      const double d = double(t[c]) - r[c];
      squared += d * d;
      relative += relative_squared(t[c], r[c]);
      absolute += std::abs(d) / (std::abs(double(r[c])) + kCompareEpsilon);
    }
    relative_y += relative_squared(luminance(t, channels), luminance(r, channels));
  }
  if (m.compared_pixels == 0) {
    m.rmse = m.relmse = m.mape = m.relmse_luminance = kNaN;
    return m;
  }
  const double values = double(m.compared_pixels) * double(channels);
  m.rmse = std::sqrt(squared / values);
  m.relmse = relative / values;
  m.mape = absolute / values;
  m.relmse_luminance = relative_y / double(m.compared_pixels);
  return m;
}

std::vector<float> relative_error_map(const ImageLayer &test, const ImageLayer &ref, uint32_t width,
                                      uint32_t height) {
  const size_t channels = test.channel_names.size();
  const size_t pixels = size_t(width) * height;
  std::vector<float> error(pixels, std::numeric_limits<float>::quiet_NaN());
  if (channels == 0 || channels != ref.channel_names.size() || test.data.size() != pixels * channels ||
      ref.data.size() != pixels * channels)
    return error;
  for (size_t p = 0; p < pixels; ++p) {
    const float *t = &test.data[p * channels];
    const float *r = &ref.data[p * channels];
    if (!finite_pixel(t, channels) || !finite_pixel(r, channels)) continue;
    double sum = 0;
    for (size_t c = 0; c < channels; ++c) sum += relative_squared(t[c], r[c]);
    error[p] = static_cast<float>(sum / double(channels));
  }
  return error;
}

Status write_error_heatmap(const std::string &path, const std::vector<float> &error, uint32_t width,
                           uint32_t height, const HeatmapScale &scale) {
  if (error.size() != size_t(width) * height)
    return Error{"cannot write '" + path + "': error map size mismatch"};
  std::vector<uint8_t> rgb(error.size() * 3);
  const double span = scale.log10_max - scale.log10_min;
  for (size_t p = 0; p < error.size(); ++p) {
    std::array<uint8_t, 3> colour = {255, 0, 255};
    if (std::isfinite(error[p])) {
      // log10(0) is -inf, which clamps to the bottom of the map like any error below the scale.
      const double e = std::max(double(error[p]), 0.0);
      colour = viridis(e > 0 ? (std::log10(e) - scale.log10_min) / span : 0.0);
    }
    std::copy(colour.begin(), colour.end(), &rgb[p * 3]);
  }
  ImagePart png{image_desc(width, height, {"R", "G", "B"}, PixelType::UInt8), rgb.data()};
  png.desc.attributes.push_back(text_attribute("Software", "Nimbus " NIMBUS_VERSION_STRING));
  png.desc.attributes.push_back(text_attribute("Description", heatmap_legend(scale)));
  return write_atomically(path, [&](const std::string &tmp) { return write_png_file(tmp, png); });
}

std::string heatmap_legend(const HeatmapScale &scale) {
  char text[256];
  std::snprintf(
      text, sizeof text,
      "per-pixel relative squared error (t-r)^2/(r^2+%g), channel mean, log scale: viridis from dark "
      "purple (<= 1e%+g) through teal (1e%+g) to yellow (>= 1e%+g); magenta = NaN/Inf",
      kCompareEpsilon, scale.log10_min, 0.5 * (scale.log10_min + scale.log10_max), scale.log10_max);
  return text;
}

}  // namespace nimbus
