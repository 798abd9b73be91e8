// Reference-free error estimate for --target-error: beauty samples of odd iterations are also summed in
// a second (half) film, so the even-iteration mean follows by subtraction. For two independent halves of
// equal size, the variance of the full mean is a quarter of the variance of their difference:
//   relMSE ~ mean over pixels of ((odd - even)^2 / 4) / (full^2 + 0.01)   (on luminance),
// the same relMSE definition as `nimbus compare`. Exists only when a target error was asked for.
#pragma once

#include <cstdint>
#include <memory>

#include "film/film.hpp"

namespace nimbus {

class ErrorEstimate {
 public:
  ErrorEstimate(uint32_t width, uint32_t height, uint32_t workers);

  // Iterations are 1-based: odd ones also go into the half film.
  static bool is_odd(uint64_t iteration) { return iteration & 1; }
  Film &half() { return half_; }
  // After the full film finished iteration `iteration` (its splats merged).
  void end_iteration(uint64_t iteration);
  // The estimate for the full film (needs an even number of iterations >= 2; else infinity).
  double relmse(const Film &full) const;

 private:
  Film half_;
};

}  // namespace nimbus
