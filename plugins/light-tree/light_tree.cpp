// nimbus.lights.tree: a many-light hierarchy. Finite lights live in a BVH whose nodes carry spatial
// and directional bounds; next-event estimation walks it from the root, choosing a child in proportion
// to its importance for the receiving point, so that of 10,000 lights the few that matter are sampled.
// Infinite lights (sun, environment) are chosen with a fixed probability beside the tree. Photon emission
// (receiver-independent) uses power-proportional selection.
#include <nimbus/nimbus.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/alias_table.hpp"
#include "light_bounds.hpp"

namespace nimbus::lights {
namespace {

const char *const kRequired[] = {"nimbus.host.lights@1", nullptr};

struct Node {
  NodeBounds bounds;
  uint32_t child_or_light =
      0;  // interior: index of the second child (the first follows the node); leaf: light
  bool leaf = false;
};

class LightTree final : public sdk::LightSampler {
 public:
  NIMBUS_DESCRIPTOR("nimbus.lights.tree", "Many-light BVH sampler (Conty & Kulla 2018)", "Nimbus",
                    NIMBUS_KIND_LIGHT_SAMPLER, 1, 0, 0, nullptr, kRequired)

  nimbus_status_t init() override {
    lights_ = host().service<nimbus_host_lights_v1_t>(NIMBUS_SERVICE_LIGHTS);
    return lights_ ? NIMBUS_OK : NIMBUS_E_UNSUPPORTED;
  }

  nimbus_status_t prepare(const nimbus_scene_info_t &) override {
    const uint32_t n = lights_->count(host().get());
    nodes_.clear();
    infinite_.clear();
    trail_.assign(n, 0);
    leaf_of_.assign(n, NIMBUS_NONE);
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
    emission_ = AliasTable(power);
    if (!finite.empty()) build(finite, 0, finite.size(), 0, 0);
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
    while (!nodes_[node].leaf) {
      const uint32_t c0 = node + 1, c1 = nodes_[node].child_or_light;
      const float i0 = nodes_[c0].bounds.importance(p, n), i1 = nodes_[c1].bounds.importance(p, n);
      if (!(i0 + i1 > 0)) return NIMBUS_NONE;
      const float p0 = i0 / (i0 + i1);
      if (u < p0) {
        u = std::min(u / p0, 0x1.fffffep-1f), prob *= p0, node = c0;
      } else {
        u = std::min((u - p0) / (1 - p0), 0x1.fffffep-1f), prob *= 1 - p0, node = c1;
      }
    }
    *pmf = prob;
    return nodes_[node].child_or_light;
  }

  float pmf(const nimbus_interaction_t &ix, uint32_t light) override {
    if (light >= leaf_of_.size()) return 0;
    if (std::find(infinite_.begin(), infinite_.end(), light) != infinite_.end())
      return p_infinite_ / float(infinite_.size());
    if (leaf_of_[light] == NIMBUS_NONE) return 0;
    // Follow the light's bit trail from the root, multiplying the same probabilities pick() uses.
    const Vec3f p = Vec3f::load(ix.p), n = Vec3f::load(ix.ns);
    uint64_t trail = trail_[light];
    float prob = 1 - p_infinite_;
    uint32_t node = 0;
    while (!nodes_[node].leaf) {
      const uint32_t c0 = node + 1, c1 = nodes_[node].child_or_light;
      const float i0 = nodes_[c0].bounds.importance(p, n), i1 = nodes_[c1].bounds.importance(p, n);
      if (!(i0 + i1 > 0)) return 0;
      const bool second = trail & 1;
      prob *= (second ? i1 : i0) / (i0 + i1);
      node = second ? c1 : c0;
      trail >>= 1;
    }
    return prob;
  }

  uint32_t pick_emitter(float u, float *pmf) override {
    const int64_t i = emission_.sample(u, pmf);
    return i < 0 ? NIMBUS_NONE : uint32_t(i);
  }

 private:
  // Builds the subtree of lights [begin, end) (depth-first layout: first child right after its parent)
  // and returns its node index. `trail`/`depth`: the branch bits from the root (1 = second child).
  uint32_t build(std::vector<std::pair<uint32_t, LightBounds>> &lights, size_t begin, size_t end,
                 uint64_t trail, int depth) {
    const uint32_t index = uint32_t(nodes_.size());
    nodes_.emplace_back();
    if (end - begin == 1) {
      LightBounds b = lights[begin].second;
      nodes_[index] = {NodeBounds(b), lights[begin].first, true};
      trail_[lights[begin].first] = trail;
      leaf_of_[lights[begin].first] = index;
      return index;
    }
    LightBounds all;
    Vec3f clo{kInfinity}, chi{-kInfinity};
    for (size_t i = begin; i < end; ++i) {
      all = bounds_union(all, lights[i].second);
      const Vec3f c = lights[i].second.centroid();
      clo = min(clo, c), chi = max(chi, c);
    }
    // Deep in the tree, split at the median so that the depth stays below the 64-bit trail's limit
    // whatever the heuristic would do with pathological light layouts.
    size_t mid = depth < 40 ? split(lights, begin, end, all, clo, chi) : (begin + end) / 2;
    build(lights, begin, mid, trail, depth + 1);
    const uint32_t second = build(lights, mid, end, trail | (uint64_t(1) << depth), depth + 1);
    nodes_[index] = {NodeBounds(all), second, false};
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
  std::vector<Node> nodes_;
  std::vector<uint32_t> infinite_;
  std::vector<uint64_t> trail_;
  std::vector<uint32_t> leaf_of_;
  AliasTable emission_;
  float p_infinite_ = 0;
};

}  // namespace
}  // namespace nimbus::lights

NIMBUS_PLUGIN_LIBRARY(nimbus::lights::LightTree)
