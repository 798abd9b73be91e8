// Photons and the photon map: an implicit balanced kd-tree over the photons in tree order (median split
// on the widest axis, every leaf at the same depth with 4 to 8 photons), queried with a per-query radius.
// A kd-tree rather than a hash grid because the merge radius varies over orders of magnitude within one
// image (spec section 4). The tree is a pure function of the photon array: the top levels are split on
// one thread, the subtrees below are built concurrently on disjoint ranges, so any thread count gives
// the same tree. It is built over 16-byte keys (position, index), which nth_element moves faster than
// photons. Every leaf at one depth lets a lookup descend on node indices alone (no ranges); leaves keep
// positions as 8 x, 8 y, 8 z (padded with NaN), compared 4 at a time, and a photon's other 32 bytes
// are loaded only when it lies within r. Against leaves of <= 8 at varying depth scanned one position
// at a time: -81 M instructions per pool iteration (-2.4 %, 3,385 -> 3,304 M), 55.3 -> 62.7 bytes per
// photon (padding), same photons found (image relMSE 5e-18: summation order). On the pool a lookup that
// passes the occupancy filter tests ~15 photons to find ~0.4 (bench/photon_map_bench.cpp models it). A hash
// grid of cell edge 4 r (prototyped in that benchmark) was only ~20 % faster there and needs one radius
// per pass.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <vector>

#include "core/math.hpp"
#include "occupancy_filter.hpp"
#include "parallel.hpp"

namespace nimbus::caustics {

// Unit vector <-> two 16-bit octahedral coordinates (Cigolle et al. 2014), packed in 32 bits.
inline uint32_t encode_octahedral(const Vec3f &v) {
  const float l1 = std::abs(v.x) + std::abs(v.y) + std::abs(v.z);
  float x = v.x / l1, y = v.y / l1;
  if (v.z < 0) {
    const float ox = (1 - std::abs(y)) * (x >= 0 ? 1.0f : -1.0f);
    const float oy = (1 - std::abs(x)) * (y >= 0 ? 1.0f : -1.0f);
    x = ox, y = oy;
  }
  // Round to nearest by adding one half and truncating (the value is >= 0): std::lround is a libm call
  // (0.4 % of the solver's instructions on the pool).
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
  float A, B;       // MIS state (mis.hpp, PhotonMis) at arrival
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

// A photon as the photon tracer stores it: 44 bytes. The map keeps positions and the rest apart.
struct Photon : PhotonData {
  float p[3];  // position, world space
  Vec3f position() const { return Vec3f::load(p); }
};
static_assert(sizeof(Photon) == 44, "photon layout");

class PhotonKdTree {
 public:
  static constexpr size_t kLeafSize = 8;

  // Copies `photons` into the map, in tree order: positions (in leaf blocks) and the rest apart.
  // Queries with radii up to `reach` (if > 0) first ask an occupancy filter whether any photon is near.
  void build(const std::vector<Photon> &photons, const ParallelFor &parallel = serial_for, float reach = 0) {
    n_ = photons.size();
    // Every leaf sits at depth_, the least depth at which ceil(n / 2^depth) <= 8; the halving splits then
    // give each leaf floor or ceil of n / 2^depth_ photons: 4 to 8 when depth_ > 0.
    depth_ = 0;
    while (((n_ + (size_t(1) << depth_) - 1) >> depth_) > kLeafSize) ++depth_;
    const size_t leaves = size_t(1) << depth_;
    nodes_.assign(leaves - 1, Node{});
    lo_ = Vec3f(kInfinity), hi_ = Vec3f(-kInfinity);
    // The tree is built over 16-byte keys (position, photon index), which nth_element moves faster than
    // 44-byte photons; the same comparisons on the same positions give the same permutation.
    std::vector<Key> keys(n_);
    // Keys and bounds in chunks (serial work here is time the camera pass waits for).
    constexpr size_t kChunk = 8192;
    const size_t chunks = (n_ + kChunk - 1) / kChunk;
    std::vector<Vec3f> chunk_lo(chunks, Vec3f(kInfinity)), chunk_hi(chunks, Vec3f(-kInfinity));
    parallel(chunks, [&](size_t c) {
      for (size_t i = c * kChunk; i < std::min(n_, (c + 1) * kChunk); ++i) {
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
    std::vector<Range> pending{Range{0, 0, n_, 0}};
    for (uint32_t level = 0; level < std::min(kTopLevels, depth_); ++level) {
      parallel(pending.size(), [&](size_t i) { split_node(keys.data(), pending[i]); });
      std::vector<Range> next;
      for (const Range &nd : pending) {
        const size_t mid = nd.lo + (nd.hi - nd.lo) / 2;
        next.push_back(Range{2 * nd.id + 1, nd.lo, mid, level + 1});
        next.push_back(Range{2 * nd.id + 2, mid, nd.hi, level + 1});
      }
      pending.swap(next);
    }
    parallel(pending.size(), [&](size_t i) { build_range(keys.data(), pending[i]); });
    // Leaf blocks in leaf order (leaf l is node 2^depth_ - 1 + l), positions apart from the rest:
    // lookups scan positions, and most photons they test are farther than r, so their other 32 bytes are
    // never loaded.
    blocks_.assign(leaves, LeafBlock{});
    leaf_begin_.resize(leaves + 1);
    data_.resize(n_);
    constexpr size_t kLeavesPerTask = 1024;
    parallel((leaves + kLeavesPerTask - 1) / kLeavesPerTask, [&](size_t t) {
      for (size_t l = t * kLeavesPerTask; l < std::min(leaves, (t + 1) * kLeavesPerTask); ++l) {
        // The leaf's range, as the builder's halving made it (bit b of l: the branch at depth_ - 1 - b).
        size_t lo = 0, hi = n_;
        for (uint32_t b = depth_; b-- > 0;) {
          const size_t mid = lo + (hi - lo) / 2;
          ((l >> b) & 1 ? lo : hi) = mid;
        }
        leaf_begin_[l] = uint32_t(lo);
        LeafBlock &blk = blocks_[l];
        for (size_t k = lo; k < hi; ++k) {
          for (int a = 0; a < 3; ++a) blk.p[a][k - lo] = keys[k].p[a];
          data_[k] = photons[keys[k].index];
        }
      }
    });
    leaf_begin_[leaves] = uint32_t(n_);
    filter_.build(
        n_, reach, [&](size_t i) { return Vec3f::load(keys[i].p); }, parallel);
  }

  size_t size() const { return n_; }
  const PhotonData *data() const { return data_.data(); }  // in tree order
  // Bytes of the map: photons, kd-tree nodes, occupancy filter.
  size_t bytes() const {
    return n_ * sizeof(PhotonData) + blocks_.size() * sizeof(LeafBlock) +
           leaf_begin_.size() * sizeof(uint32_t) + nodes_.size() * sizeof(Node) + filter_.bytes();
  }
  float filter_reach() const { return filter_.reach(); }

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
  // dx*dx + dy*dy + dz*dz), in tree order.
  template <class F>
  void query(const Vec3f &q, float r, F &&f) const {
    if (!may_hold(q, r)) return;
    const float r2 = r * r;
    const float qa[3] = {q.x, q.y, q.z};  // indexed by the split axis: a load, not Vec3f's branches
    const uint32_t first_leaf = uint32_t(nodes_.size());  // every node below it is internal
    uint32_t stack[64];                                   // far children; at most one per level
    int top = 0;
    uint32_t id = 0;
    for (;;) {
      // Descend to the leaf containing q, remembering far children the sphere reaches.
      while (id < first_leaf) {
        const Node nd = nodes_[id];
        const float d = qa[nd.axis] - nd.split;
        // Left holds p[a] <= split, right p[a] >= split. A point within r of q has |p[a] - q[a]| no
        // smaller than |split - q[a]| on the far side (float subtraction is monotonic), and its
        // computed d2 is no smaller than that square, so this never prunes a point the leaf accepts.
        const uint32_t right = d > 0;
        if (d * d <= r2) stack[top++] = 2 * id + 2 - right;
        id = 2 * id + 1 + right;
      }
      scan_leaf(id - first_leaf, q, r2, f);
      if (top == 0) return;
      id = stack[--top];
    }
  }

 private:
  struct Range {
    size_t id, lo, hi;
    uint32_t level;
  };

  struct Key {
    float p[3];      // the photon's position
    uint32_t index;  // the photon's index in the caller's order
  };

  // A leaf's positions by axis, unused slots NaN (no d2 <= r^2 holds for them, even for r = inf): one
  // loop over 8 lanes that the compiler turns into vector compares.
  struct alignas(32) LeafBlock {
    LeafBlock() { std::fill(&p[0][0], &p[0][0] + 3 * kLeafSize, std::numeric_limits<float>::quiet_NaN()); }
    float p[3][kLeafSize];
  };

  // Calls f for the leaf's photons within r, in order. Two 4-wide halves (GCC/Clang vector extensions:
  // SSE here, scalar code where a target has none); most scanned leaves hold none.
  template <class F>
  void scan_leaf(uint32_t leaf, const Vec3f &q, float r2, F &f) const {
    using V4 = float __attribute__((vector_size(16)));
    using M4 = int32_t __attribute__((vector_size(16)));
    static_assert(kLeafSize == 8, "two halves of four");
    const LeafBlock &b = blocks_[leaf];
    V4 d2[2];
    M4 within[2];
    for (int h = 0; h < 2; ++h) {
      V4 x, y, z;
      std::memcpy(&x, &b.p[0][4 * h], sizeof(V4));
      std::memcpy(&y, &b.p[1][4 * h], sizeof(V4));
      std::memcpy(&z, &b.p[2][4 * h], sizeof(V4));
      const V4 dx = x - q.x, dy = y - q.y, dz = z - q.z;
      d2[h] = dx * dx + dy * dy + dz * dz;
      within[h] = d2[h] <= r2;
    }
    uint64_t any[2];
    const M4 either = within[0] | within[1];
    std::memcpy(any, &either, sizeof(any));
    if ((any[0] | any[1]) == 0) return;
    const PhotonData *data = data_.data() + leaf_begin_[leaf];
    for (uint32_t k = 0; k < kLeafSize; ++k)
      if (within[k >> 2][k & 3]) f(data[k], d2[k >> 2][k & 3]);
  }

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
      if (nd.level >= depth_) continue;
      split_node(keys, nd);
      const size_t mid = nd.lo + (nd.hi - nd.lo) / 2;
      stack.push_back(Range{2 * nd.id + 1, nd.lo, mid, nd.level + 1});
      stack.push_back(Range{2 * nd.id + 2, mid, nd.hi, nd.level + 1});
    }
  }

  size_t n_ = 0;
  uint32_t depth_ = 0;  // of every leaf
  struct Node {
    float split = 0;
    uint32_t axis = 0;
  };
  std::vector<Node> nodes_;           // internal nodes in heap order: 2^depth_ - 1
  std::vector<LeafBlock> blocks_;     // positions, one block per leaf, in leaf order
  std::vector<uint32_t> leaf_begin_;  // leaf l's first photon in tree order; leaf_begin_[2^depth_] = n
  std::vector<PhotonData> data_;      // in tree order
  Vec3f lo_, hi_;                     // bounds of all photons
  OccupancyFilter filter_;
};

}  // namespace nimbus::caustics
