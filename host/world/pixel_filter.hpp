// Pixel reconstruction filters, applied by filter importance sampling (pbrt-v4 section 8.8): each
// camera sample's offset from the pixel centre is drawn from the filter itself, and its weight
// f / pdf is ~1, so every sample still lands in exactly one pixel. Tiles stay disjoint (no locks, the
// same image at any thread count) and the film's per-pixel mean is the filtered estimate.
#pragma once

#include <string>

#include <nimbus/cpp/distribution.hpp>
#include <nimbus/cpp/math.hpp>
#include "scene/pixel_filter_type.hpp"

namespace nimbus {

class PixelFilter {
 public:
  // Box: radius 0.5 (the pixel); Gaussian: radius 1.5, sigma 0.5; Blackman-Harris: radius 2 (the
  // defaults of pbrt-v4 and Mitsuba 3 for the same filters).
  explicit PixelFilter(FilterType type = FilterType::Box);

  FilterType type() const { return type_; }
  float radius() const { return radius_; }
  // Offset from the pixel centre in pixels, and the sample's weight (its expectation is 1).
  Vec2f sample(float u0, float u1, float &weight) const;
  // The filter normalised to integrate to 1 over its support.
  float evaluate(float x, float y) const;

 private:
  float raw(float x, float y) const;
  FilterType type_;
  float radius_ = 0.5f;
  float norm_ = 1;  // 1 / integral of raw()
  static constexpr int kTable = 64;
  Distribution2D table_;
};

}  // namespace nimbus
