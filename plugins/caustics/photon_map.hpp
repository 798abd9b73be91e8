// Photons and the photon map: an implicit balanced kd-tree over the photons in tree order (median split
// on the widest axis, leaves of at most 8 photons), queried with a per-query radius.
// A kd-tree rather than a hash grid because the merge radius varies over orders of magnitude within one
// image (spec section 4). The tree is a pure function of the photon array: the top levels are split on
// one thread, the subtrees below are built concurrently on disjoint ranges, so any thread count gives
// the same tree. It is built over 16-byte keys (position, index), which nth_element moves faster than
// photons. Lookups scan an array of positions and load a photon's other 32 bytes only when it lies
// within r, since most photons a leaf scan tests lie outside it (bench/photon_map_bench.cpp models the
// pool's lookups). Hash grids and other layouts of the map were no faster in the renderer: a lookup is
// bound by one cache miss per structure it touches (table, cell ranges, positions), whatever the index
// (docs/performance.md §6).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

#include <nimbus/cpp/math.hpp>
#include <nimbus/cpp/tasks.hpp>
#include "occupancy_filter.hpp"

namespace nimbus::caustics {

using sdk::parallel_ranges;
using sdk::ParallelFor;
using sdk::serial_for;

// Unit vector <-> two 16-bit octahedral coordinates (Cigolle et al. 2014), packed in 32 bits.
inline uint32_t encode_octahedral(const Vec3f &v) {
  const float l1 = std::abs(v.x) + std::abs(v.y) + std::abs(v.z);
  float x = v.x / l1, y = v.y / l1;
  if (v.z < 0) {
    const float ox = (1 - std::abs(y)) * (x >= 0 ? 1.0f : -1.0f);
    const float oy = (1 - std::abs(x)) * (y >= 0 ? 1.0f : -1.0f);
    x = ox, y = oy;
  }
  // Round to nearest by adding one half and truncating (the value is >= 0): std::lround is a libm call,
  // and this runs for every photon stored.
  const auto q = [](float f) { return uint32_t(clamp(f * 0.5f + 0.5f, 0.0f, 1.0f) * 65535.0f + 0.5f); };
  return q(x) | (q(y) << 16);
}

inline Vec3f decode_octahedral(uint32_t e) {
  const float x = float(e & 0xffffu) / 65535.0f * 2 - 1, y = float(e >> 16) / 65535.0f * 2 - 1;
  Vec3f v(x, y, 1 - std::abs(x) - std::abs(y));
  if (v.z < 0) {
    const float ox = (1 - std::abs(y)) * (x >= 0 ? 1.0f : -1.0f);
    const float oy = (1 - std::abs(x)) * (y >= 0 ? 1.0f : -1.0f);
    v.x = ox, v.y = oy;
  }
  return normalize(v);
}

// What a lookup reads of a photon besides its position: 32 bytes.
struct PhotonData {
  uint32_t dir;     // octahedral: the incoming direction, pointing back to where the photon came from
  uint32_t normal;  // octahedral: geometric normal at p (side test)
  float power[3];   // flux carried, before division by the pass's photon path count
  float A, B;       // MIS state (mis.hpp, PhotonMis) at arrival: log2 A and log2 B
  uint32_t bits;    // depth (6) | prev_rough (1) | b_valid (1) | light index (24)

  static constexpr uint32_t kMaxLight = (1u << 24) - 1;
  uint32_t depth() const { return bits & 63u; }  // photon vertices x_s .. x_{k-1}, i.e. k - s
  bool prev_rough() const { return (bits >> 6) & 1u; }
  bool b_valid() const { return (bits >> 7) & 1u; }
  uint32_t light() const { return bits >> 8; }
  static uint32_t pack(uint32_t depth, bool prev_rough, bool b_valid, uint32_t light) {
    return (depth & 63u) | (prev_rough ? 64u : 0u) | (b_valid ? 128u : 0u) |
           (std::min(light, kMaxLight) << 8);
  }
};
static_assert(sizeof(PhotonData) == 32, "photon layout");

// A photon as the photon tracer stores it: 64 bytes. The map keeps positions and the rest apart.
struct Photon : PhotonData {
  float p[3];     // position, world space
  uint32_t path;  // the photon path it belongs to: its index in its chunk, then in the pass (path_use.hpp)
  // log2 of PhotonMis::B_importance and B_importance2, folded into B once the pass's guide totals are
  // known (guided_pass.cpp, fold_importance)
  float B_importance, B_importance2;
  float time_u;  // its path's time as a share of the exposure (photon_windows.hpp); 0 when nothing moves
  float lambda;  // its wavelength (nm) after a dispersive vertex, its power then the value at it; else 0
  // log2 of rho = mis(lp_lt / lp) against the light-tracing technique (light_paths.hpp; -inf: none)
  float lt;
  Vec3f position() const { return Vec3f::load(p); }
};
static_assert(sizeof(Photon) == 68, "photon layout");

class PhotonKdTree {
 public:
  static constexpr size_t kLeafSize = 8;

  // Copies `photons` into the map, in tree order: positions (12 bytes) and the rest (32 bytes) apart.
  // Queries with radii up to `reach` (if > 0) first ask an occupancy filter whether any photon is near.
  // with_times, with_lambdas: keep the photons' times and wavelengths too (only when something moves or
  // disperses light, spec 7).
  void build(const std::vector<Photon> &photons, const ParallelFor &parallel = serial_for, float reach = 0,
             bool with_times = false, bool with_lambdas = false, bool with_lt = false) {
    n_ = photons.size();
    uint32_t depth = 0;
    while (((n_ + (size_t(1) << depth) - 1) >> depth) > kLeafSize) ++depth;
    nodes_.assign((size_t(1) << (depth + 1)), Node{});
    lo_ = Vec3f(kInfinity), hi_ = Vec3f(-kInfinity);
    // The tree is built over 16-byte keys (position, photon index), which nth_element moves faster than
    // 64-byte photons; the same comparisons on the same positions give the same permutation.
    std::vector<Key> &keys = keys_;  // kept from build to build, as the arrays below (no page faults)
    keys.resize(n_);
    // Keys and bounds in chunks, and below the copies in tree order: serial work in a photon pass is
    // time the camera pass waits for (on 2 cores each serial step counts twice).
    constexpr size_t kChunk = 8192;
    const size_t chunks = (n_ + kChunk - 1) / kChunk;
    std::vector<Vec3f> chunk_lo(chunks, Vec3f(kInfinity)), chunk_hi(chunks, Vec3f(-kInfinity));
    parallel_ranges(parallel, n_, kChunk, [&](size_t b, size_t e) {
      const size_t c = b / kChunk;
      for (size_t i = b; i < e; ++i) {
        const Vec3f p = photons[i].position();
        keys[i] = Key{{p.x, p.y, p.z}, uint32_t(i)};
        chunk_lo[c] = min(chunk_lo[c], p), chunk_hi[c] = max(chunk_hi[c], p);
      }
    });
    for (size_t c = 0; c < chunks; ++c) lo_ = min(lo_, chunk_lo[c]), hi_ = max(hi_, chunk_hi[c]);
    // The top levels one level at a time (the nodes of a level in parallel), until there are enough
    // subtrees to share out; then the subtrees. Each node's split depends only on its own range, so the
    // tree is the same whatever runs where.
    constexpr uint32_t kTopLevels = 6;
    std::vector<Range> pending{Range{0, 0, n_}};
    for (uint32_t level = 0; level < kTopLevels; ++level) {
      std::vector<Range> next;
      for (const Range &nd : pending)
        if (nd.hi - nd.lo > kLeafSize) next.push_back(nd);
      parallel(next.size(), [&](size_t i) { split_node(keys.data(), next[i]); });
      pending.clear();
      for (const Range &nd : next) {
        const size_t mid = nd.lo + (nd.hi - nd.lo) / 2;
        pending.push_back(Range{2 * nd.id + 1, nd.lo, mid});
        pending.push_back(Range{2 * nd.id + 2, mid, nd.hi});
      }
    }
    parallel(pending.size(), [&](size_t i) { build_range(keys.data(), pending[i]); });
    // Positions and the rest in tree order, apart: lookups scan positions, and most photons they test
    // are farther than r, so their other 32 bytes are never loaded.
    positions_.resize(n_);
    data_.resize(n_);
    paths_.resize(n_);
    times_.resize(with_times ? n_ : 0);
    lambdas_.resize(with_lambdas ? n_ : 0);
    lts_.resize(with_lt ? n_ : 0);
    parallel_ranges(parallel, n_, kChunk, [&](size_t b, size_t e) {
      for (size_t k = b; k < e; ++k) {
        const Photon &ph = photons[keys[k].index];
        positions_[k] = Vec3f::load(keys[k].p), data_[k] = ph, paths_[k] = ph.path;
        if (with_times) times_[k] = ph.time_u;
        if (with_lambdas) lambdas_[k] = ph.lambda;
        if (with_lt) lts_[k] = ph.lt;
      }
    });
    filter_.build(
        n_, reach, [&](size_t i) { return positions_[i]; }, parallel);
  }

  size_t size() const { return n_; }
  const PhotonData *data() const { return data_.data(); }  // in tree order
  // Bytes of the map: photons, kd-tree nodes, occupancy filter.
  size_t bytes() const {
    return n_ * (sizeof(Vec3f) + sizeof(PhotonData)) +
           (times_.size() + lambdas_.size() + lts_.size()) * sizeof(float) + nodes_.size() * sizeof(Node) +
           filter_.bytes();
  }
  float filter_reach() const { return filter_.reach(); }
  // The photon path of a photon query() handed out.
  uint32_t path_of(const PhotonData &ph) const { return paths_[size_t(&ph - data_.data())]; }
  // The time (share of the exposure) of a photon query() handed out (a map built with_times).
  float time_of(const PhotonData &ph) const { return times_[size_t(&ph - data_.data())]; }
  // The wavelength of a photon query() handed out (a map built with_lambdas; 0 for an RGB photon).
  float lambda_of(const PhotonData &ph) const { return lambdas_[size_t(&ph - data_.data())]; }
  bool has_lambdas() const { return !lambdas_.empty(); }
  // A photon's log2 rho against the light-tracing technique (a map built with_lt; else -inf: none).
  float lt_of(const PhotonData &ph) const {
    return lts_.empty() ? -kInfinity : lts_[size_t(&ph - data_.data())];
  }

  // False only if no photon lies within r of q: the map's bounds, then the occupancy filter. query()
  // asks it first; most lookups end there.
  bool may_hold(const Vec3f &q, float r) const {
    if (n_ == 0 || !(r >= 0)) return false;
    const float r2 = r * r;
    if (sqr(std::max({lo_.x - q.x, 0.0f, q.x - hi_.x})) + sqr(std::max({lo_.y - q.y, 0.0f, q.y - hi_.y})) +
            sqr(std::max({lo_.z - q.z, 0.0f, q.z - hi_.z})) >
        r2 * 1.0001f)
      return false;
    return filter_.may_hold(q, r);
  }

  // Calls f(PhotonData, squared distance) for every photon with |p - q|^2 <= r^2 (computed in float as
  // dx*dx + dy*dy + dz*dz), in tree order. Returns the leaves it scanned (0 when may_hold turned the
  // query away): the lookup's cost, which grows with the photons around q whether or not any lies
  // within r.
  template <class F>
  uint32_t query(const Vec3f &q, float r, F &&f) const {
    if (!may_hold(q, r)) return 0;
    uint32_t leaves = 0;
    const float r2 = r * r;
    const float qa[3] = {q.x, q.y, q.z};  // indexed by the split axis: a load, not Vec3f's branches
    struct Item {
      uint32_t id, lo, hi;
    };
    Item stack[64];
    int top = 0;
    uint32_t id = 0, lo = 0, hi = uint32_t(n_);
    for (;;) {
      // Descend to the leaf containing q, remembering far children the sphere reaches.
      while (hi - lo > kLeafSize) {
        const Node nd = nodes_[id];
        const uint32_t mid = lo + (hi - lo) / 2;
        const float d = qa[nd.axis] - nd.split;
        // Left holds p[a] <= split, right p[a] >= split. A point within r of q has |p[a] - q[a]| no
        // smaller than |split - q[a]| on the far side (float subtraction is monotonic), and its
        // computed d2 is no smaller than that square, so this never prunes a point the leaf accepts.
        const bool right = d > 0;
        if (d * d <= r2) stack[top++] = right ? Item{2 * id + 1, lo, mid} : Item{2 * id + 2, mid, hi};
        id = right ? 2 * id + 2 : 2 * id + 1;
        (right ? lo : hi) = mid;
      }
      ++leaves;
      for (uint32_t i = lo; i < hi; ++i) {
        const Vec3f &p = positions_[i];
        const float dx = p.x - q.x, dy = p.y - q.y, dz = p.z - q.z;
        const float d2 = dx * dx + dy * dy + dz * dz;
        if (d2 <= r2) f(data_[i], d2);
      }
      if (top == 0) return leaves;
      const Item it = stack[--top];
      id = it.id, lo = it.lo, hi = it.hi;
    }
  }

 private:
  struct Range {
    size_t id, lo, hi;
  };

  struct Key {
    float p[3];      // the photon's position
    uint32_t index;  // the photon's index in the caller's order
  };

  // Partitions one node of `keys`: median on the widest axis of the range's bounds.
  void split_node(Key *keys, const Range &nd) {
    Vec3f lo(kInfinity), hi(-kInfinity);
    for (size_t i = nd.lo; i < nd.hi; ++i) {
      const Vec3f p = Vec3f::load(keys[i].p);
      lo = min(lo, p), hi = max(hi, p);
    }
    const Vec3f ext = hi - lo;
    const uint32_t a = ext.x >= ext.y && ext.x >= ext.z ? 0u : (ext.y >= ext.z ? 1u : 2u);
    nodes_[nd.id].axis = a;
    const size_t mid = nd.lo + (nd.hi - nd.lo) / 2;
    std::nth_element(keys + nd.lo, keys + mid, keys + nd.hi,
                     [a](const Key &x, const Key &y) { return x.p[a] < y.p[a]; });
    nodes_[nd.id].split = keys[mid].p[a];  // the children permute their ranges later: keep it
  }

  void build_range(Key *keys, const Range &root) {
    std::vector<Range> stack{root};
    while (!stack.empty()) {
      const Range nd = stack.back();
      stack.pop_back();
      if (nd.hi - nd.lo <= kLeafSize) continue;
      split_node(keys, nd);
      const size_t mid = nd.lo + (nd.hi - nd.lo) / 2;
      stack.push_back(Range{2 * nd.id + 1, nd.lo, mid});
      stack.push_back(Range{2 * nd.id + 2, mid, nd.hi});
    }
  }

  size_t n_ = 0;
  struct Node {
    float split = 0;
    uint32_t axis = 0;
  };
  std::vector<Node> nodes_;       // internal nodes in heap order
  std::vector<Vec3f> positions_;  // in tree order
  std::vector<PhotonData> data_;  // in tree order
  std::vector<uint32_t> paths_;   // in tree order: each photon's path
  std::vector<float> times_;      // in tree order: each photon's time (maps built with_times)
  std::vector<float> lambdas_;    // in tree order: each photon's wavelength (maps built with_lambdas)
  std::vector<float> lts_;        // in tree order: each photon's log2 rho (maps built with_lt)
  std::vector<Key> keys_;         // build()'s scratch
  Vec3f lo_, hi_;                 // bounds of all photons
  OccupancyFilter filter_;
};

}  // namespace nimbus::caustics
