// The MIS state's numbers (mis.hpp): squared pdf ratios and their products as doubles that share a
// power-of-two scale, renormalised as they grow or shrink so that their ratios stay exact over paths
// whose products leave double's range (up to 32 vertices, pdfs over many decades).
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

namespace nimbus::caustics {

// MIS state values: squared pdf ratios and their products.
using Mis = double;
// The MIS exponent beta = 2 applied to one factor.
inline float mis(float x) { return x * x; }
inline Mis mis(Mis x) { return x * x; }
// x * 2^n, rounded as std::ldexp rounds it (the product with a power of two is rounded once), without
// its library call in the paths' inner loops; n beyond the normal exponents goes to std::ldexp.
inline Mis times_pow2(Mis x, int n) {
  if (n < -1022 || n > 1023) return std::ldexp(x, n);
  return x * std::bit_cast<Mis>(uint64_t(n + 1023) << 52);
}
// a * b * 2^n, with the exponents summed apart when the product a * b alone would leave double's normal
// range: a state scaled by 2^n far from 1 times a factor far from 1 can lie well within it.
inline Mis scaled_product(Mis a, Mis b, int n) {
  const Mis ab = a * b;
  if (std::abs(ab) >= std::numeric_limits<Mis>::min() && std::abs(ab) <= std::numeric_limits<Mis>::max())
    return times_pow2(ab, n);
  if (a == 0 || b == 0) return 0.0;
  int ea = 0, eb = 0;
  const Mis ma = std::frexp(a, &ea), mb = std::frexp(b, &eb);
  return std::ldexp(ma * mb, ea + eb + n);
}
// The values are renormalised when the largest leaves [2^-kMisRescale, 2^kMisRescale].
inline constexpr int kMisRescale = 400;
// Moves the power of two of the largest of `values` (if out of range) into exp2; values 2^800 below
// the largest become 0 (they no longer change any weight).
template <class Get>
inline void renormalise(uint32_t n, Get &&value, int &exp2) {
  Mis largest = 0;
  for (uint32_t i = 0; i < n; ++i) largest = std::max(largest, value(i));
  if (!(largest > 0) || !std::isfinite(largest) ||
      (largest < times_pow2(1.0, kMisRescale) && largest > times_pow2(1.0, -kMisRescale)))
    return;
  const int e = std::ilogb(largest);
  for (uint32_t i = 0; i < n; ++i) value(i) = times_pow2(value(i), -e);
  exp2 += e;
}
// x * 2^-exp2, a new term to add to `values` (scaled by 2^exp2): when the term would lie beyond the
// rescale range above them, they are first rescaled to its power of two (those 2^800 below become 0).
template <class Get>
inline Mis scaled_term(Mis x, uint32_t n, Get &&value, int &exp2) {
  if (x > times_pow2(1.0, exp2 + kMisRescale) && x <= std::numeric_limits<Mis>::max()) {
    const int e = std::ilogb(x);
    for (uint32_t i = 0; i < n; ++i) value(i) = times_pow2(value(i), exp2 - e);
    exp2 = e;
  }
  return times_pow2(x, -exp2);
}
// log2 of x * 2^exp2, as a photon stores A and B (-inf for 0).
inline float stored_log2(Mis x, int exp2) {
  return x > 0 ? float(std::log2(x) + exp2) : -std::numeric_limits<float>::infinity();
}

// A sum of camera terms R (times 2^exp2): the value of sum * factor, and whether it overflowed.
struct MisSum {
  Mis sum = 0;
  int exp2 = 0;
  Mis times(Mis factor, bool &clamped) const {
    const Mis v = scaled_product(sum, factor, exp2);
    if (!(v <= std::numeric_limits<Mis>::max())) clamped = true;
    return v;
  }
};

}  // namespace nimbus::caustics
