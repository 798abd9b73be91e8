// A conservative "could any photon lie within r of q?" test in front of the photon kd-tree.
// On the caustic scenes most camera lookups find no photon at all, and the tree needs a descent and leaf
// scans to find that out. The filter answers with one hash and one bit: a bit set per grid cell (edge
// 2 reach) that some photon's box [p - reach, p + reach] overlaps, hashed into a bit array. A photon
// within r <= reach of q has q inside its box, so q's cell is marked: the filter never hides a photon;
// hash collisions only let a lookup through to the tree. Queries with r > reach always go through.
// `reach` comes from the radii the previous iteration's lookups used (RadiusHistogram), so the filter
// costs nothing in accuracy and changes no result.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include <nimbus/cpp/math.hpp>
#include <nimbus/cpp/rng.hpp>
#include <nimbus/cpp/tasks.hpp>

namespace nimbus::caustics {

using sdk::parallel_ranges;
using sdk::ParallelFor;
using sdk::serial_for;

class OccupancyFilter {
 public:
  static constexpr size_t kParallelPhotons = 16384;  // maps this large mark their cells in two halves

  // Marks the cells around n positions, position(i) for i in [0, n). reach <= 0 (or not finite), or no
  // position: no filter, every query goes through. Large maps mark in two halves concurrently, the
  // second into a bit array of its own that is then ORed in: the same bits whatever runs where. (Marking
  // is serial time the camera pass waits for; one array with atomic ORs from two threads is slower.)
  template <class Position>
  void build(size_t n, float reach, Position &&position, const ParallelFor &parallel = serial_for) {
    bits_.clear();
    reach_ = -1;
    if (n == 0 || !(reach > 0) || !std::isfinite(reach)) return;
    // Boxes are grown by a relative 1e-3: a photon the query's float d^2 <= r^2 accepts may lie a few
    // ulps beyond r.
    const double grown = double(reach) * 1.001;
    Vec3f lo(kInfinity);
    for (size_t i = 0; i < n; ++i) lo = min(lo, position(i));
    for (int a = 0; a < 3; ++a) origin_[a] = double(lo[a]) - grown;
    // Cells of edge 2 reach: a photon marks <= 8. Finer cells mark more (up to 27 at edge `reach`), for
    // a longer build and hardly fewer lookups let through (docs/performance.md §6). 64 bits per photon
    // keep hash collisions, which let lookups through, rare where photons are sparse. The blocked layout
    // below puts neighbouring cells on one line, which neighbouring lookups share.
    inv_cell_ = 1 / (2 * grown);
    lines_ = (n + 7) / 8;  // 64 bits per photon
    bits_.assign(lines_, Line{});
    const bool halves = n >= kParallelPhotons;
    std::vector<Line> &second = second_;
    second.assign(halves ? lines_ : 0, Line{});
    parallel_ranges(parallel, n, halves ? (n + 1) / 2 : n, [&](size_t begin, size_t end) {
      Line *bits = begin == 0 ? bits_.data() : second.data();
      for (size_t i = begin; i < end; ++i) {
        const Vec3f p = position(i);
        uint64_t c0[3], c1[3];
        for (int a = 0; a < 3; ++a)
          c0[a] = cell(double(p[a]) - grown, a), c1[a] = cell(double(p[a]) + grown, a);
        for (uint64_t x = c0[0]; x <= c1[0]; ++x)
          for (uint64_t y = c0[1]; y <= c1[1]; ++y)
            for (uint64_t z = c0[2]; z <= c1[2]; ++z) set(bits, x, y, z);
      }
    });
    if (halves) {
      parallel_ranges(parallel, lines_, 4096, [&](size_t b, size_t e) {
        for (size_t l = b; l < e; ++l)
          for (int w = 0; w < 8; ++w) bits_[l].w[w] |= second[l].w[w];
      });
    }
    reach_ = reach;
  }

  // False only if no photon lies within r of q.
  bool may_hold(const Vec3f &q, float r) const {
    if (!(r <= reach_)) return true;
    return test(cell(q.x, 0), cell(q.y, 1), cell(q.z, 2));
  }

  float reach() const { return reach_; }
  size_t bytes() const { return bits_.size() * sizeof(Line); }

 private:
  // Monotonic in v: the floor of a double clamped to [0, 2^62] (truncation is the floor there, and
  // inline, where std::floor is a libm call on baseline x86-64). Positions inside the map's bounds give
  // values >= 0; the clamp only keeps far-away values from overflowing.
  uint64_t cell(double v, int a) const {
    return uint64_t(std::clamp((v - origin_[a]) * inv_cell_, 0.0, 4.6e18));
  }
  // Blocked layout: the 8x8x8 cells of a block share one 64-byte line, chosen by the block's hash
  // mapped onto the lines by a multiply-shift (Lemire; no power-of-two size needed); the cell's place
  // in its block picks the bit. Neighbouring lookups (neighbouring pixels) then read the same line,
  // where one hashed bit per cell would cost a cache miss per lookup.
  struct alignas(64) Line {
    uint64_t w[8] = {};
  };
  size_t line(uint64_t x, uint64_t y, uint64_t z) const {
    const uint64_t h = mix64((x >> 3) * 0x9e3779b97f4a7c15ULL ^ (y >> 3) * 0xc2b2ae3d27d4eb4fULL ^
                             (z >> 3) * 0x165667b19e3779f9ULL);
    return size_t((unsigned __int128)h * lines_ >> 64);
  }
  static uint32_t local(uint64_t x, uint64_t y, uint64_t z) {
    return uint32_t((x & 7) | (y & 7) << 3 | (z & 7) << 6);
  }
  void set(Line *bits, uint64_t x, uint64_t y, uint64_t z) const {
    const uint32_t b = local(x, y, z);
    bits[line(x, y, z)].w[b >> 6] |= uint64_t(1) << (b & 63);
  }
  bool test(uint64_t x, uint64_t y, uint64_t z) const {
    const uint32_t b = local(x, y, z);
    return (bits_[line(x, y, z)].w[b >> 6] >> (b & 63)) & 1;
  }

  std::vector<Line> bits_;
  std::vector<Line> second_;  // build()'s scratch: the second half's bits, kept from build to build
  uint64_t lines_ = 0;
  double origin_[3] = {0, 0, 0}, inv_cell_ = 0;
  float reach_ = -1;  // < 0: no filter
};

// Counts of lookup radii in four bins per octave: the radius below which a given share of lookups fall,
// independent of the order the counts were added in (so of threads).
class RadiusHistogram {
 public:
  void add(float r) {
    if (!(r > 0) || !std::isfinite(r)) return;
    int e = 0;
    const float m = std::frexp(r, &e);  // r = m 2^e, m in [0.5, 1)
    const int sub = std::min(kPerOctave - 1, int((m - 0.5f) * 2 * kPerOctave));
    ++counts_[size_t(std::clamp((e - kMinExp) * kPerOctave + sub, 0, kBins - 1))];
  }
  void add(const RadiusHistogram &o) {
    for (int i = 0; i < kBins; ++i) counts_[i] += o.counts_[i];
  }
  void clear() { counts_.fill(0); }
  // The counts themselves, for saving and restoring a render's state.
  std::span<uint64_t> counts() { return counts_; }
  std::span<const uint64_t> counts() const { return counts_; }
  uint64_t total() const {
    uint64_t t = 0;
    for (uint64_t c : counts_) t += c;
    return t;
  }
  // The upper edge of the bin in which the share q of all radii is reached (0 when empty): at least a
  // share q of the radii are <= it.
  float quantile(double q) const {
    const uint64_t t = total();
    if (t == 0) return 0;
    uint64_t sum = 0;
    for (int i = 0; i < kBins; ++i) {
      sum += counts_[i];
      if (double(sum) >= q * double(t)) {
        const int e = i / kPerOctave + kMinExp, sub = i % kPerOctave;
        return std::ldexp(0.5f + 0.5f * float(sub + 1) / kPerOctave, e);
      }
    }
    return kInfinity;
  }

 private:
  static constexpr int kPerOctave = 4, kMinExp = -126, kMaxExp = 128;
  static constexpr int kBins = (kMaxExp - kMinExp) * kPerOctave;
  std::array<uint64_t, kBins> counts_{};
};

}  // namespace nimbus::caustics
