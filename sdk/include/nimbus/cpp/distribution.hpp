// Piecewise-constant distributions for continuous sampling (pbrt-v4 ch. A.1 and A.5): 1-D over [0,1)
// and 2-D over [0,1)^2 (marginal over rows, conditional within a row). The host samples environment
// maps and pixel filters with them, the caustics solver its emission maps. Tables are flat float
// arrays: an environment sample binary-searches one contiguous row instead of chasing a per-row
// allocation of doubles, because on large maps that search is bound by cache misses, not arithmetic.
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

namespace nimbus {

namespace detail {

// Normalised cdf (n + 1 entries, last exactly 1) of the n weights f (negative weights count as 0);
// uniform when they sum to 0. Returns the integral of f over [0,1) (its mean).
inline double build_cdf(std::span<const float> f, float *cdf) {
  const size_t n = f.size();
  double sum = 0;
  for (float x : f) sum += double(std::max(x, 0.0f));
  double running = 0;  // in double: float sums of thousands of texels lose the small ones
  cdf[0] = 0;
  for (size_t i = 0; i < n; ++i) {
    running += double(std::max(f[i], 0.0f));
    cdf[i + 1] = sum > 0 ? float(running / sum) : float(double(i + 1) / double(n));
  }
  cdf[n] = 1;
  return sum / double(n);
}

// x in [0,1) with the piecewise-constant density of cdf (n + 1 entries); *bin receives the bin.
inline float sample_cdf(const float *cdf, size_t n, float u, size_t &bin) {
  // Last index with cdf <= u, among the first n.
  const size_t i = size_t(std::upper_bound(cdf, cdf + n + 1, u) - cdf);
  bin = std::min(i == 0 ? 0 : i - 1, n - 1);
  float du = u - cdf[bin];
  const float width = cdf[bin + 1] - cdf[bin];
  if (width > 0) du /= width;
  return std::min((float(bin) + std::clamp(du, 0.0f, 1.0f)) / float(n), 0x1.fffffep-1f);
}

}  // namespace detail

class Distribution1D {
 public:
  Distribution1D() = default;
  // Weights >= 0 over n equal bins of [0,1). All-zero weights sample uniformly (pdf 1) so that callers
  // never divide by zero; `integral()` then reports 0 so they can tell.
  explicit Distribution1D(std::vector<float> f) : func_(std::move(f)), cdf_(func_.size() + 1) {
    if (!func_.empty()) integral_ = detail::build_cdf(func_, cdf_.data());
  }

  size_t size() const { return func_.size(); }
  double integral() const { return integral_; }

  // Returns x in [0,1) with density pdf(x); *bin receives the bin index.
  float sample(float u, float *pdf, size_t *bin = nullptr) const {
    size_t o = 0;
    const float x = detail::sample_cdf(cdf_.data(), func_.size(), u, o);
    if (pdf) *pdf = bin_pdf(o);
    if (bin) *bin = o;
    return x;
  }
  float pdf(float x) const {
    if (func_.empty()) return 0;
    return bin_pdf(std::min(size_t(x * float(func_.size())), func_.size() - 1));
  }

 private:
  float bin_pdf(size_t o) const { return integral_ > 0 ? float(double(func_[o]) / integral_) : 1.0f; }

  std::vector<float> func_;
  std::vector<float> cdf_;
  double integral_ = 0;
};

class Distribution2D {
 public:
  Distribution2D() = default;
  // f is row-major: height rows of width values; u runs along a row, v across rows.
  Distribution2D(const std::vector<float> &f, size_t width, size_t height)
      : width_(width), height_(height), conditional_cdf_(height * (width + 1)), pdf_(width * height) {
    std::vector<float> row_integral(height);
    for (size_t y = 0; y < height; ++y)
      row_integral[y] = float(detail::build_cdf(std::span(f).subspan(y * width, width),
                                                conditional_cdf_.data() + y * (width + 1)));
    marginal_ = Distribution1D(row_integral);
    // Joint density of a cell: marginal pdf of its row times the conditional pdf within the row (uniform
    // in a row that has no weight, which the marginal then never picks).
    for (size_t y = 0; y < height; ++y) {
      const float pv = marginal_.pdf((float(y) + 0.5f) / float(height));
      for (size_t x = 0; x < width; ++x)
        pdf_[y * width + x] =
            row_integral[y] > 0 ? pv * std::max(f[y * width + x], 0.0f) / row_integral[y] : pv;
    }
  }

  bool empty() const { return pdf_.empty(); }
  double integral() const { return marginal_.integral(); }
  size_t width() const { return width_; }
  size_t height() const { return height_; }

  // (u, v) in [0,1)^2 with density *pdf; *cell receives the row-major index of the cell.
  void sample(float u0, float u1, float &u, float &v, float *pdf, size_t *cell = nullptr) const {
    size_t row = 0, col = 0;
    v = marginal_.sample(u1, nullptr, &row);
    u = detail::sample_cdf(conditional_cdf_.data() + row * (width_ + 1), width_, u0, col);
    if (pdf) *pdf = pdf_[row * width_ + col];
    if (cell) *cell = row * width_ + col;
  }
  float pdf(float u, float v) const {
    const size_t row = std::min(size_t(v * float(height_)), height_ - 1);
    const size_t col = std::min(size_t(u * float(width_)), width_ - 1);
    return pdf_[row * width_ + col];
  }
  // The density of cell (row-major index), as pdf() and sample() report it.
  float cell_pdf(size_t cell) const { return pdf_[cell]; }

 private:
  size_t width_ = 0, height_ = 0;
  std::vector<float> conditional_cdf_;  // height rows of width + 1 entries
  std::vector<float> pdf_;              // joint density per cell
  Distribution1D marginal_;
};

}  // namespace nimbus
