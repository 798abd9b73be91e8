// Piecewise-constant distributions for continuous sampling (pbrt-v4 ch. A.1 and A.5): 1-D over [0,1)
// and 2-D over [0,1)^2 (marginal over rows, conditional within a row). Used to importance-sample
// environment maps.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

namespace nimbus {

class Distribution1D {
 public:
  Distribution1D() = default;
  // Weights >= 0 over n equal bins of [0,1). All-zero weights sample uniformly (pdf 1) so that callers
  // never divide by zero; `integral()` then reports 0 so they can tell.
  explicit Distribution1D(std::vector<float> f) : func_(std::move(f)), cdf_(func_.size() + 1) {
    const size_t n = func_.size();
    cdf_[0] = 0;
    for (size_t i = 1; i <= n; ++i) cdf_[i] = cdf_[i - 1] + double(std::max(func_[i - 1], 0.0f)) / double(n);
    integral_ = cdf_[n];
    if (integral_ == 0) {
      for (size_t i = 1; i <= n; ++i) cdf_[i] = double(i) / double(n);
    } else {
      for (size_t i = 1; i <= n; ++i) cdf_[i] /= integral_;
    }
  }

  size_t size() const { return func_.size(); }
  double integral() const { return integral_; }

  // Returns x in [0,1) with density pdf(x); *bin receives the bin index.
  float sample(float u, float *pdf, size_t *bin = nullptr) const {
    // Last index with cdf <= u.
    const size_t i = size_t(std::upper_bound(cdf_.begin(), cdf_.end(), double(u)) - cdf_.begin()) - 1;
    const size_t o = std::min(i, func_.size() - 1);
    double du = double(u) - cdf_[o];
    const double width = cdf_[o + 1] - cdf_[o];
    if (width > 0) du /= width;
    if (pdf) *pdf = integral_ > 0 ? float(double(func_[o]) / integral_) : 1.0f;
    if (bin) *bin = o;
    return std::min(float((double(o) + du) / double(func_.size())), 0x1.fffffep-1f);
  }
  float pdf(float x) const {
    if (func_.empty()) return 0;
    const size_t o = std::min(size_t(x * float(func_.size())), func_.size() - 1);
    return integral_ > 0 ? float(double(func_[o]) / integral_) : 1.0f;
  }

 private:
  std::vector<float> func_;
  std::vector<double> cdf_;
  double integral_ = 0;
};

class Distribution2D {
 public:
  Distribution2D() = default;
  // f is row-major: height rows of width values; u runs along a row, v across rows.
  Distribution2D(const std::vector<float> &f, size_t width, size_t height) : width_(width), height_(height) {
    std::vector<float> marginal(height);
    rows_.reserve(height);
    for (size_t y = 0; y < height; ++y) {
      rows_.emplace_back(std::vector<float>(f.begin() + y * width, f.begin() + (y + 1) * width));
      marginal[y] = float(rows_.back().integral());
    }
    marginal_ = Distribution1D(std::move(marginal));
  }

  bool empty() const { return rows_.empty(); }
  double integral() const { return marginal_.integral(); }

  // (u, v) in [0,1)^2 with density *pdf.
  void sample(float u0, float u1, float &u, float &v, float *pdf) const {
    float pdf_v = 0, pdf_u = 0;
    size_t row = 0;
    v = marginal_.sample(u1, &pdf_v, &row);
    u = rows_[row].sample(u0, &pdf_u);
    if (pdf) *pdf = pdf_u * pdf_v;
  }
  float pdf(float u, float v) const {
    const size_t row = std::min(size_t(v * float(height_)), height_ - 1);
    return marginal_.pdf(v) * rows_[row].pdf(u);
  }

 private:
  size_t width_ = 0, height_ = 0;
  std::vector<Distribution1D> rows_;
  Distribution1D marginal_;
};

}  // namespace nimbus
