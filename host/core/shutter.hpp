// The camera's shutter: the interval [open, close] of scene time during which the film is exposed, and
// its curve, the relative exposure over the interval (piecewise linear over the interval normalised to
// [0, 1]; a box when none is given, as a mechanical shutter that opens and closes at once). Camera and
// photon paths draw their times from its density g (caustics solver spec 7.1); photon power carries
// 1 / g(t) like any sampled dimension.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace nimbus {

class Shutter {
 public:
  // An instantaneous shutter at time 0: nothing is sampled.
  Shutter() = default;
  // open <= close; curve: knots (x in [0, 1], increasing from 0 to 1; relative exposure y >= 0, not all
  // zero) or empty for a box. The scene parser checks these and names the offending key.
  Shutter(float open, float close, std::vector<std::array<float, 2>> curve = {})
      : open_(open), close_(close) {
    if (curve.empty()) curve = {{{0.0f, 1.0f}}, {{1.0f, 1.0f}}};
    for (const auto &k : curve) x_.push_back(k[0]), y_.push_back(std::max(0.0f, k[1]));
    cdf_.assign(x_.size(), 0.0);
    for (size_t i = 1; i < x_.size(); ++i)
      cdf_[i] = cdf_[i - 1] + 0.5 * (double(y_[i - 1]) + y_[i]) * (double(x_[i]) - x_[i - 1]);
    box_ = x_.size() == 2 && y_[0] == 1 && y_[1] == 1;
    last_ = std::nextafter(close_, open_);
  }

  float open() const { return open_; }
  float close() const { return close_; }
  // Nothing moves within an instantaneous shutter, so no time is sampled.
  bool instantaneous() const { return !(close_ > open_); }

  // The time that u in [0, 1) maps to, distributed with density pdf().
  float sample(float u) const {
    if (instantaneous()) return open_;
    // The box's segment fraction is u itself (the general solve below gives exactly that): every camera
    // path of a moving scene draws its time here.
    if (box_) return std::min(float(open_ + double(u) * (double(close_) - open_)), last_);
    const double target = double(u) * cdf_.back();
    size_t i = size_t(std::upper_bound(cdf_.begin(), cdf_.end(), target) - cdf_.begin());
    i = std::clamp<size_t>(i, 1, x_.size() - 1);
    const double w = double(x_[i]) - x_[i - 1], c = (target - cdf_[i - 1]) / std::max(w, 1e-30);
    const double y0 = y_[i - 1], dy = double(y_[i]) - y0;
    // Solves y0 s + dy s^2 / 2 = c for the segment fraction s, in the form stable for dy -> 0.
    const double root = std::sqrt(std::max(0.0, y0 * y0 + 2 * dy * c));
    const double s = y0 + root > 0 ? std::clamp(2 * c / (y0 + root), 0.0, 1.0) : 0.5;
    const double x = x_[i - 1] + s * w;
    return std::min(float(open_ + x * (double(close_) - open_)), last_);
  }
  // The density g of sampled times per unit of scene time (0 outside [open, close]).
  float pdf(float t) const {
    if (instantaneous() || !(t >= open_ && t <= close_)) return 0;
    const double x = (double(t) - open_) / (double(close_) - open_);
    size_t i = size_t(std::upper_bound(x_.begin(), x_.end(), float(x)) - x_.begin());
    i = std::clamp<size_t>(i, 1, x_.size() - 1);
    const double w = double(x_[i]) - x_[i - 1];
    const double s = w > 0 ? std::clamp((x - x_[i - 1]) / w, 0.0, 1.0) : 0.0;
    const double y = y_[i - 1] + s * (double(y_[i]) - y_[i - 1]);
    return float(y / (cdf_.back() * (double(close_) - open_)));
  }

 private:
  float open_ = 0, close_ = 0;
  std::vector<float> x_, y_;  // the curve's knots
  std::vector<double> cdf_;   // its integral at the knots
  bool box_ = false;          // the curve is the box (0, 1), (1, 1)
  float last_ = 0;            // the latest time drawn: the float before close
};

}  // namespace nimbus
