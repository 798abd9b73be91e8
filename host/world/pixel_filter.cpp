#include "world/pixel_filter.hpp"

#include <vector>

namespace nimbus {
namespace {

float gaussian(float x, float sigma, float radius) {
  // Shifted so the filter reaches zero at its radius (pbrt-v4 GaussianFilter).
  const auto g = [&](float v) { return std::exp(-v * v / (2 * sigma * sigma)); };
  return std::max(0.0f, g(x) - g(radius));
}

float blackman_harris(float x, float radius) {
  // 4-term Blackman-Harris window over [-radius, radius].
  const float t = (x / radius + 1) * 0.5f;  // 0..1
  if (t < 0 || t > 1) return 0;
  constexpr float a0 = 0.35875f, a1 = 0.48829f, a2 = 0.14128f, a3 = 0.01168f;
  return a0 - a1 * std::cos(2 * kPi * t) + a2 * std::cos(4 * kPi * t) - a3 * std::cos(6 * kPi * t);
}

}  // namespace

PixelFilter::PixelFilter(FilterType type) : type_(type) {
  radius_ = type == FilterType::Box ? 0.5f : type == FilterType::Gaussian ? 1.5f : 2.0f;
  if (type == FilterType::Box) return;
  // Tabulate |f| for sampling and integrate f (midpoint rule on a fine grid) for the normalisation.
  std::vector<float> f(kTable * kTable);
  double integral = 0;
  const float cell = 2 * radius_ / kTable;
  for (int y = 0; y < kTable; ++y)
    for (int x = 0; x < kTable; ++x) {
      const float v = raw(-radius_ + (x + 0.5f) * cell, -radius_ + (y + 0.5f) * cell);
      f[y * kTable + x] = std::abs(v);
      integral += double(v) * cell * cell;
    }
  norm_ = float(1.0 / integral);
  table_ = Distribution2D(f, kTable, kTable);
}

float PixelFilter::raw(float x, float y) const {
  switch (type_) {
    case FilterType::Box:
      return std::abs(x) <= 0.5f && std::abs(y) <= 0.5f ? 1.0f : 0.0f;
    case FilterType::Gaussian:
      return gaussian(x, 0.5f, radius_) * gaussian(y, 0.5f, radius_);
    case FilterType::BlackmanHarris:
      return blackman_harris(x, radius_) * blackman_harris(y, radius_);
  }
  return 0;
}

float PixelFilter::evaluate(float x, float y) const { return raw(x, y) * norm_; }

Vec2f PixelFilter::sample(float u0, float u1, float &weight) const {
  if (type_ == FilterType::Box) {
    weight = 1;
    return {u0 - 0.5f, u1 - 0.5f};
  }
  float u, v, pdf;
  table_.sample(u0, u1, u, v, &pdf);
  const Vec2f p{(2 * u - 1) * radius_, (2 * v - 1) * radius_};
  // pdf is over the unit square; over the filter's support it is pdf / (2 r)^2.
  const float pdf_support = pdf / sqr(2 * radius_);
  weight = pdf_support > 0 ? evaluate(p.x, p.y) / pdf_support : 0;
  return p;
}

}  // namespace nimbus
