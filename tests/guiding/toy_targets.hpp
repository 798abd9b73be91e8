// Targets of the guiding tests on [0, 1)^dims, with the integrals the tests compare against in closed form.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>

namespace nimbus::guide_test {

// caustics-solver.md §10 (iv): 0 on [0, 0.3), 1/(u - 0.25)^2 on [0.3, 0.9), 0 on [0.9, 0.95), a spike of
// 400 on [0.95, 0.96), 0 on [0.96, 1). Graded (a state's T decides how long it is kept, so HJ11's skipped
// mutation shows), with a gap the mutation rarely jumps and a spike only the exchange finds reliably.
struct SpikyTarget {
  static double at(double u) {
    if (u >= 0.3 && u < 0.9) return 1.0 / ((u - 0.25) * (u - 0.25));
    return u >= 0.95 && u < 0.96 ? 400.0 : 0.0;
  }
  // The integral of T over [a, b): the antiderivative -1/(u - 0.25) on the graded part, 400 u on the spike.
  static double integral(double a, double b) {
    double sum = 0;
    if (const double lo = std::max(a, 0.3), hi = std::min(b, 0.9); hi > lo)
      sum += 1 / (lo - 0.25) - 1 / (hi - 0.25);
    if (const double lo = std::max(a, 0.95), hi = std::min(b, 0.96); hi > lo) sum += 400 * (hi - lo);
    return sum;
  }
  // b = (20 - 1/0.65) + 4 = 22.4615.
  static double normalisation() { return integral(0, 1); }
  // Standard deviation of T(u) for u uniform, relative to b: E[T^2] = (1/3)(0.05^-3 - 0.65^-3) + 400^2 0.01
  // = 4265.5, so sqrt(4265.5 - b^2) / b = 2.730.
  static constexpr double kRelativeSigma = 2.730;
};

// A function whose integral the chain's mixture estimator must find: g(u) = 1 + u T(u), nonzero where T
// is 0 (only uniform paths see it there) and weighted towards the spike. Its integral is 1 + (ln 13 +
// 0.25 (20 - 1/0.65)) + 400 * 0.01 * 0.955 = 12.000334 (u/(u - 1/4)^2 = 1/(u - 1/4) + (1/4)/(u - 1/4)^2).
struct SpikyIntegrand {
  static double at(double u) { return 1 + u * SpikyTarget::at(u); }
  static double integral() { return 1 + std::log(13.0) + 0.25 * (20 - 1 / 0.65) + 400 * 0.01 * 0.955; }
};

// A Gaussian bump of width `sigma` at the centre of [0, 1)^dims: smooth and graded, positive everywhere
// (no chain starts uniform-only), narrow enough that the mutation size matters.
struct GaussianBump {
  double sigma = 0.03;
  double at(std::span<const float> u) const {
    double r2 = 0;
    for (float x : u) r2 += (double(x) - 0.5) * (double(x) - 0.5);
    return std::exp(-r2 / (2 * sigma * sigma));
  }
};

}  // namespace nimbus::guide_test
