// nimbus.lights.tree: a many-light hierarchy. Finite lights live in a BVH whose nodes carry spatial
// and directional bounds; next-event estimation walks it from the root, choosing a child in proportion
// to its importance for the receiving point, so that of 10,000 lights the few that matter are sampled.
// The BVH is built binary (pbrt-v4's split heuristic) and collapsed into 4-wide nodes whose four
// importances are one SIMD evaluation.
// Infinite lights (sun, environment) are chosen with a fixed probability beside the tree. Photon emission
// (receiver-independent) follows the integrator's feedback by the SDK kit's rule (emitter_selection.hpp),
// by power before any.
#include <nimbus/nimbus.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include <nimbus/cpp/alias_table.hpp>
#include <nimbus/cpp/emitter_selection.hpp>
#include "light_bounds.hpp"

namespace nimbus::lights {
namespace {

const char *const kRequired[] = {"nimbus.host.lights@1", nullptr};

// A binary BVH node while building: the collapse into WideNodes reads the bounds of grandchildren.
struct BinaryNode {
  LightBounds bounds;
  uint32_t first = 0, second = 0;  // children, or first = the light of a leaf
  bool leaf = false;
};

// Where a light or a wide node hangs: parent wide node and lane.
struct Slot {
  uint32_t node = NIMBUS_NONE;
  uint8_t lane = 0;
};

class LightTree final : public sdk::LightSampler {
 public:
  NIMBUS_DESCRIPTOR("nimbus.lights.tree", "Many-light BVH sampler (Conty & Kulla 2018)", "Nimbus",
                    NIMBUS_KIND_LIGHT_SAMPLER, 1, 0, 0, nullptr, kRequired)

  nimbus_status_t init() override {
    lights_ = host().service<nimbus_host_lights_v1_t>(NIMBUS_SERVICE_LIGHTS);
    return lights_ ? NIMBUS_OK : NIMBUS_E_UNSUPPORTED;
  }

  nimbus_status_t prepare(const nimbus_scene_info_t &scene) override {
    if (nimbus_status_t s = emission_.prepare(host().get(), lights_, scene); s != NIMBUS_OK) return s;
    const uint32_t n = lights_->count(host().get());
    nodes_.clear();
    parent_.clear();
    infinite_.clear();
    leaf_of_.assign(n, Slot{});
    std::vector<double> power(n, 0.0);
    std::vector<std::pair<uint32_t, LightBounds>> finite;
    for (uint32_t i = 0; i < n; ++i) {
      nimbus_light_info_t info{};
      info.header.struct_size = sizeof(info);
      if (lights_->info(host().get(), i, &info) != NIMBUS_OK) return NIMBUS_E_INTERNAL;
      power[i] = std::isfinite(info.power) && info.power > 0 ? info.power : 0.0;
      if (info.flags & NIMBUS_LIGHT_INFINITE) {
        if (power[i] > 0) infinite_.push_back(i);
        continue;
      }
      const LightBounds b = bounds_of(info);
      if (b.phi > 0) finite.emplace_back(i, b);
    }
    if (!finite.empty()) {
      std::vector<BinaryNode> binary;
      binary.reserve(2 * finite.size());
      build(finite, 0, finite.size(), 0, binary);
      collapse(binary, 0, Slot{});
    }
    const float slots = float(infinite_.size()) + (nodes_.empty() ? 0.0f : 1.0f);
    p_infinite_ = slots > 0 ? float(infinite_.size()) / slots : 0.0f;
    return NIMBUS_OK;
  }

  uint32_t pick(const nimbus_interaction_t &ix, float u, float *pmf) override {
    *pmf = 0;
    if (u < p_infinite_) {
      const float x = u / p_infinite_ * float(infinite_.size());
      const size_t i = std::min(size_t(x), infinite_.size() - 1);
      *pmf = p_infinite_ / float(infinite_.size());
      return infinite_[i];
    }
    if (nodes_.empty()) return NIMBUS_NONE;
    u = std::min((u - p_infinite_) / (1 - p_infinite_), 0x1.fffffep-1f);
    const Vec3f p = Vec3f::load(ix.p), n = Vec3f::load(ix.ns);
    float prob = 1 - p_infinite_;
    uint32_t node = 0;
    for (;;) {
      float imp[WideNode::kWidth];
      const float sum = importances(node, p, n, imp);
      if (!(sum > 0)) return NIMBUS_NONE;
      // The lane whose share of [0, sum) holds u * sum; never a zero-importance lane.
      int last = WideNode::kWidth - 1;
      while (!(imp[last] > 0)) --last;
      const float x = u * sum;
      float below = 0;
      int k = 0;
      while (k < last && !(imp[k] > 0 && x < below + imp[k])) below += imp[k++];
      prob *= imp[k] / sum;
      u = std::clamp((x - below) / imp[k], 0.0f, 0x1.fffffep-1f);
      if (nodes_[node].leaf_mask & (1u << k)) {
        *pmf = prob;
        return nodes_[node].child[k];
      }
      node = nodes_[node].child[k];
    }
  }

  float pmf(const nimbus_interaction_t &ix, uint32_t light) override {
    if (light >= leaf_of_.size()) return 0;
    if (std::find(infinite_.begin(), infinite_.end(), light) != infinite_.end())
      return p_infinite_ / float(infinite_.size());
    if (leaf_of_[light].node == NIMBUS_NONE) return 0;
    // The slots from the light up to the root, then the same products pick() forms, root first.
    Slot path[kMaxDepth];
    int depth = 0;
    for (Slot at = leaf_of_[light]; at.node != NIMBUS_NONE; at = parent_[at.node]) path[depth++] = at;
    const Vec3f p = Vec3f::load(ix.p), n = Vec3f::load(ix.ns);
    float prob = 1 - p_infinite_;
    while (depth > 0) {
      const Slot at = path[--depth];
      float imp[WideNode::kWidth];
      const float sum = importances(at.node, p, n, imp);
      if (!(sum > 0) || !(imp[at.lane] > 0)) return 0;
      prob *= imp[at.lane] / sum;
    }
    return prob;
  }

  uint32_t pick_emitter(float u, float *pmf) override { return emission_.pick(u, pmf); }
  bool adapts_emission() const override { return true; }
  nimbus_status_t update_emission(const nimbus_emission_feedback_t &f) override {
    return emission_.update(f);
  }
  float pmf_emitter(uint32_t light) override { return emission_.pmf(light); }

 private:
  // The four lanes' importances at a node and their sum, summed the same way for pick() and pmf() so that
  // both report bit-identical probabilities.
  float importances(uint32_t node, const Vec3f &p, const Vec3f &n, float imp[WideNode::kWidth]) const {
    nodes_[node].importance(p, n, imp);
    return (imp[0] + imp[1]) + (imp[2] + imp[3]);
  }

  // Builds the binary subtree of lights [begin, end) depth first and returns its node index.
  uint32_t build(std::vector<std::pair<uint32_t, LightBounds>> &lights, size_t begin, size_t end, int depth,
                 std::vector<BinaryNode> &binary) {
    const uint32_t index = uint32_t(binary.size());
    binary.emplace_back();
    if (end - begin == 1) {
      binary[index] = {lights[begin].second, lights[begin].first, 0, true};
      return index;
    }
    LightBounds all;
    Vec3f clo{kInfinity}, chi{-kInfinity};
    for (size_t i = begin; i < end; ++i) {
      all = bounds_union(all, lights[i].second);
      const Vec3f c = lights[i].second.centroid();
      clo = min(clo, c), chi = max(chi, c);
    }
    // Deep in the tree, split at the median so that the depth stays bounded (kMaxDepth) whatever the
    // heuristic would do with pathological light layouts.
    const size_t mid = depth < 40 ? split(lights, begin, end, all, clo, chi) : (begin + end) / 2;
    const uint32_t first = build(lights, begin, mid, depth + 1, binary);
    const uint32_t second = build(lights, mid, end, depth + 1, binary);
    binary[index] = {all, first, second, false};
    return index;
  }

  // Turns binary node b into a wide node whose lanes are its children, with the interior child of most
  // power replaced by its own children until there are four; recurses into interior lanes.
  uint32_t collapse(const std::vector<BinaryNode> &binary, uint32_t b, Slot parent) {
    std::vector<uint32_t> lanes;
    if (binary[b].leaf) {
      lanes = {b};  // a single light
    } else {
      lanes = {binary[b].first, binary[b].second};
    }
    while (lanes.size() < size_t(WideNode::kWidth)) {
      int open = -1;
      for (int k = 0; k < int(lanes.size()); ++k)
        if (!binary[lanes[k]].leaf &&
            (open < 0 || binary[lanes[k]].bounds.phi > binary[lanes[open]].bounds.phi))
          open = k;
      if (open < 0) break;
      const BinaryNode &o = binary[lanes[open]];
      lanes[open] = o.first;
      lanes.push_back(o.second);
    }
    const uint32_t index = uint32_t(nodes_.size());
    nodes_.emplace_back();
    parent_.push_back(parent);
    for (int k = 0; k < int(lanes.size()); ++k) {
      const BinaryNode &c = binary[lanes[k]];
      if (c.leaf) {
        nodes_[index].set(k, c.bounds, c.first, true);
        leaf_of_[c.first] = {index, uint8_t(k)};
      } else {
        const uint32_t child = collapse(binary, lanes[k], {index, uint8_t(k)});
        nodes_[index].set(k, c.bounds, child, false);
      }
    }
    return index;
  }

  // Surface-area-orientation heuristic over 12 buckets per axis (pbrt-v4's light BVH cost), falling
  // back to a median split when all centroids coincide.
  size_t split(std::vector<std::pair<uint32_t, LightBounds>> &lights, size_t begin, size_t end,
               const LightBounds &all, const Vec3f &clo, const Vec3f &chi) {
    constexpr int kBuckets = 12;
    const Vec3f extent = all.hi - all.lo;
    const float max_extent = max_component(extent);
    float best_cost = kInfinity;
    int best_axis = -1, best_bucket = -1;
    for (int axis = 0; axis < 3; ++axis) {
      if (!(chi[axis] > clo[axis])) continue;
      LightBounds buckets[kBuckets];
      const auto bucket_of = [&](const LightBounds &b) {
        const int k = int(kBuckets * (b.centroid()[axis] - clo[axis]) / (chi[axis] - clo[axis]));
        return std::clamp(k, 0, kBuckets - 1);
      };
      for (size_t i = begin; i < end; ++i) {
        LightBounds &bk = buckets[bucket_of(lights[i].second)];
        bk = bounds_union(bk, lights[i].second);
      }
      for (int s = 0; s < kBuckets - 1; ++s) {
        LightBounds below, above;
        for (int k = 0; k <= s; ++k) below = bounds_union(below, buckets[k]);
        for (int k = s + 1; k < kBuckets; ++k) above = bounds_union(above, buckets[k]);
        const float cost =
            cost_of(below, extent[axis], max_extent) + cost_of(above, extent[axis], max_extent);
        if (cost > 0 && cost < best_cost) best_cost = cost, best_axis = axis, best_bucket = s;
      }
    }
    size_t mid = begin;
    if (best_axis >= 0) {
      const int axis = best_axis;
      const auto it = std::partition(lights.begin() + begin, lights.begin() + end, [&](const auto &l) {
        const int k = int(kBuckets * (l.second.centroid()[axis] - clo[axis]) / (chi[axis] - clo[axis]));
        return std::clamp(k, 0, kBuckets - 1) <= best_bucket;
      });
      mid = size_t(it - lights.begin());
    }
    if (mid == begin || mid == end) {
      mid = (begin + end) / 2;
      std::nth_element(lights.begin() + begin, lights.begin() + mid, lights.begin() + end,
                       [](const auto &a, const auto &b) { return a.first < b.first; });
    }
    return mid;
  }

  // Power x orientation measure x surface area, with the axis-regularisation of pbrt-v4.
  static float cost_of(const LightBounds &b, float axis_extent, float max_extent) {
    if (b.phi == 0) return 0;
    const float theta_o = std::acos(clamp(b.normals.cos_theta, -1, 1));
    const float theta_e = std::acos(clamp(b.cos_theta_e, -1, 1));
    const float theta_w = std::min(theta_o + theta_e, kPi);
    const float sin_o = std::sin(theta_o);
    const float m_omega =
        2 * kPi * (1 - std::cos(theta_o)) +
        kPi / 2 *
            (2 * theta_w * sin_o - std::cos(theta_o - 2 * theta_w) - 2 * theta_o * sin_o + std::cos(theta_o));
    const Vec3f d = b.hi - b.lo;
    const float area = 2 * (d.x * d.y + d.x * d.z + d.y * d.z);
    const float kr = axis_extent > 0 ? max_extent / axis_extent : 1;
    return b.phi * m_omega * std::max(area, 1e-12f) * kr;
  }

  const nimbus_host_lights_v1_t *lights_ = nullptr;
  // Binary depth is at most 40 + log2(lights) (median splits below 40), and collapsing never deepens.
  static constexpr int kMaxDepth = 40 + 33;
  std::vector<WideNode> nodes_;
  std::vector<Slot> parent_;  // of each wide node (root: none)
  std::vector<uint32_t> infinite_;
  std::vector<Slot> leaf_of_;  // of each light (none: infinite or no power)
  sdk::EmitterSelection emission_;
  float p_infinite_ = 0;
};

}  // namespace
}  // namespace nimbus::lights

NIMBUS_PLUGIN_LIBRARY(nimbus::lights::LightTree)
