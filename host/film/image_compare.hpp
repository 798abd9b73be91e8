// Error metrics between a test image and a reference, as `nimbus compare` reports them.
//
// With t the test value, r the reference value, per channel, and ε = kCompareEpsilon:
//   RMSE         sqrt(mean (t − r)²)
//   relMSE       mean (t − r)² / (r² + ε)         relative squared error; ε keeps black pixels from
//                                                  dominating (the usual definition in rendering papers)
//   MAPE         mean |t − r| / (|r| + ε)          mean absolute percentage error, as a fraction
//   relMSE (Y)   relMSE of the luminance Y = 0.2126 R + 0.7152 G + 0.0722 B (Rec. 709, the linear sRGB
//                primaries the film stores), per pixel rather than per channel
// Means run over every channel of every pixel that is finite in both images. A pixel with any NaN or
// infinite channel is left out of every metric and counted instead: in TEST (the renderer's bug to
// find) and in REF separately.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/expected.hpp"
#include "film/image_read.hpp"

namespace nimbus {

inline constexpr double kCompareEpsilon = 1e-2;

struct ImageMetrics {
  double rmse = 0, relmse = 0, mape = 0, relmse_luminance = 0;  // NaN when no pixel could be compared
  uint64_t pixels = 0;                                          // width * height
  uint64_t compared_pixels = 0;                                 // finite in both images
  uint64_t nonfinite_test = 0, nonfinite_reference = 0;         // pixels with a NaN or Inf channel
};

// `test` and `ref` are one layer of images of `width` x `height`, with the same number of channels (1 or
// more; the luminance of 1- or 2-channel layers is their mean channel, of wider ones Y of the first three).
// Errors: different channel counts, data not matching the size.
Expected<ImageMetrics> compare_images(const ImageLayer &test, const ImageLayer &ref, uint32_t width,
                                      uint32_t height);

// Per pixel, the relative squared error averaged over channels (the relMSE of that pixel); NaN where
// either image is not finite.
std::vector<float> relative_error_map(const ImageLayer &test, const ImageLayer &ref, uint32_t width,
                                      uint32_t height);

// The heatmap's scale: log10 of the error at the bottom and the top of the colour map. Fixed rather than
// fitted to the image, so heatmaps of different renders can be compared by eye.
struct HeatmapScale {
  double log10_min = -4, log10_max = 1;
};

// Writes `error` (from relative_error_map) as an 8-bit sRGB PNG, atomically: log10 of the error mapped
// linearly onto viridis (dark purple low, yellow high, perceptually uniform), clamped at both ends;
// non-finite pixels magenta, which viridis never produces. Zero error counts as the minimum.
Status write_error_heatmap(const std::string &path, const std::vector<float> &error, uint32_t width,
                           uint32_t height, const HeatmapScale &scale = {});

// One line describing the heatmap's colours and scale, for the command's output.
std::string heatmap_legend(const HeatmapScale &scale = {});

}  // namespace nimbus
