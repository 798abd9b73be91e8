#include "film/error_estimate.hpp"

#include <limits>

#include <nimbus/cpp/math.hpp>

namespace nimbus {

ErrorEstimate::ErrorEstimate(uint32_t width, uint32_t height, uint32_t workers) : half_(width, height) {
  (void)half_.allocate();  // beauty only (always registered, takes splats): cannot fail
  half_.set_worker_count(workers);
}

void ErrorEstimate::end_iteration(uint64_t iteration) {
  if (!is_odd(iteration)) return;
  half_.merge_splats();
  half_.end_iteration();
}

double ErrorEstimate::relmse(const Film &full) const {
  const uint64_t n = full.iterations(), n_odd = half_.iterations();
  if (n < 2 || n % 2 != 0 || 2 * n_odd != n) return std::numeric_limits<double>::infinity();
  const std::vector<float> f = full.resolve(Film::kBeauty), o = half_.resolve(Film::kBeauty);
  double sum = 0;
  const size_t pixels = f.size() / 3;
  for (size_t i = 0; i < pixels; ++i) {
    const double lf = luminance(Rgb::load(&f[3 * i])), lo = luminance(Rgb::load(&o[3 * i]));
    const double le = 2 * lf - lo;  // the even half's mean: (n lf - n/2 lo) / (n/2)
    sum += (lo - le) * (lo - le) / 4 / (lf * lf + 0.01);
  }
  return pixels ? sum / double(pixels) : 0;
}

}  // namespace nimbus
