// Stratified, spatially ordered emission samples for one photon pass.
//
// Path p of a pass of N paths takes its two emission numbers (the sun's point on its emission rectangle
// or disk, a point or spot light's direction in its cone, an area light's point) from the square's
// Hilbert curve at u = (p + xi) / N, xi uniform: the N paths split [0, 1) into N equal strata, and the
// curve maps each stratum onto a region of the square of area 1 / N. For a path whose index is uniform
// the sample is uniform over the square (the curve's cell is uniform, the point uniform in it), so the
// emission densities the MIS weights use do not change; together the pass's samples are stratified.
// Consecutive paths (one task runs 1,024 of them) start next to each other.
// Stratifying lowers the variance where the emission pair decides where photons land (the sun's point
// above the pool's water) and changes nothing elsewhere; the spatial order did not make the ray casts
// measurably cheaper.
#pragma once

#include <algorithm>
#include <cstdint>

#include <nimbus/cpp/math.hpp>

namespace nimbus::caustics {

inline constexpr uint32_t kHilbertOrder =
    16;  // the finest: 2^16 x 2^16 cells (16 per stratum up to 2^28 paths)

// Cell (x, y) of the 2^order x 2^order grid at distance d along the Hilbert curve (the classic
// iterative inverse, one quadrant rotation per level). Adjacent d give edge-adjacent cells. The rotation
// is done with masks rather than branches: its quadrants are random from path to path, and mispredicted
// branches made this loop a percent of a caustic render's time. (x < s, so s - 1 - x = x ^ (s - 1).)
inline void hilbert_cell(uint64_t d, uint32_t order, uint32_t &x, uint32_t &y) {
  x = y = 0;
  for (uint32_t s = 1; s < (uint32_t(1) << order); s <<= 1) {
    const uint32_t rx = 1 & uint32_t(d >> 1), ry = 1 & uint32_t(d ^ rx);
    const uint32_t rotate = ry - 1;                // all ones when ry == 0
    const uint32_t flip = rotate & -rx & (s - 1);  // s - 1 when ry == 0 and rx == 1
    x ^= flip, y ^= flip;
    const uint32_t swap = (x ^ y) & rotate;
    x ^= swap, y ^= swap;
    x += s * rx, y += s * ry;
    d >>= 2;
  }
}

// The curve's order for a pass of n paths: at least 16 cells per stratum (each stratum a compact run of
// cells), at most kHilbertOrder. Coarser cells cost fewer levels per sample (a pass of 2^16 paths: 10
// instead of 16) and change nothing else: the point is uniform within its cell.
inline uint32_t hilbert_order(uint64_t n) {
  uint32_t order = 2;
  while (order < kHilbertOrder && (uint64_t(1) << (2 * order)) < 16 * n) ++order;
  return order;
}

// The two emission numbers of path p of n (p < n), from xi (the stratum's jitter) and j0, j1 (the
// point's jitter in its cell), all uniform in [0, 1).
inline Vec2f emission_sample(uint64_t p, uint64_t n, float xi, float j0, float j1) {
  const uint32_t order = hilbert_order(n);
  const uint64_t cells = uint64_t(1) << (2 * order);
  const double u = (double(p) + double(xi)) / double(n > 0 ? n : 1);
  const uint64_t d = std::min(cells - 1, uint64_t(u * double(cells)));
  uint32_t x = 0, y = 0;
  hilbert_cell(d, order, x, y);
  const float cell = 1.0f / float(uint32_t(1) << order);
  constexpr float kBelowOne = 0x1.fffffep-1f;
  // float(x) + j < 2^16 keeps the sum exact to 8 bits of j; min keeps a rounded-up 1 out.
  return Vec2f{std::min((float(x) + j0) * cell, kBelowOne), std::min((float(y) + j1) * cell, kBelowOne)};
}

}  // namespace nimbus::caustics
