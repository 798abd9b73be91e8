// Useful pixels (solver spec section 5): per pixel, the accumulated luminance of MIS-weighted merges (Mp)
// and of the whole sample (Tp). A pixel counts for the photon budget when merges bring more than a
// fraction kBudgetThreshold of its light, and keeps photons coming at all when they bring more than
// kIdleThreshold (schedule.hpp).
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include <nimbus/cpp/math.hpp>

#include "schedule.hpp"

namespace nimbus::caustics {

class UsefulPixels {
 public:
  // [main-thread] Zeroes the sums of a width x height image (0: none kept).
  void reset(size_t pixels) {
    merge_.assign(pixels, 0.0f);
    total_.assign(pixels, 0.0f);
  }

  // [render-thread] One sample of pixel i (each pixel belongs to one tile, so no two threads meet).
  void add(size_t i, const Rgb &beauty, const Rgb &merged, bool map_active) {
    total_[i] += luminance(beauty);
    if (map_active) merge_[i] += luminance(merged);
  }

  // [main-thread] The shares of the `pixels` rendered pixels that are useful for the budget and for
  // staying active. Pixels outside the render region have Mp = Tp = 0 and never count.
  UsefulRatio ratios(uint64_t pixels) const {
    uint64_t budget = 0, idle = 0;
    for (size_t i = 0; i < merge_.size(); ++i) {
      budget += merge_[i] > float(kBudgetThreshold) * total_[i] ? 1 : 0;
      idle += merge_[i] > float(kIdleThreshold) * total_[i] ? 1 : 0;
    }
    const auto ratio = [&](uint64_t n) { return pixels ? std::min(1.0, double(n) / double(pixels)) : 0.0; };
    return {ratio(budget), ratio(idle)};
  }

 private:
  std::vector<float> merge_, total_;  // per pixel: Mp, Tp
};

}  // namespace nimbus::caustics
