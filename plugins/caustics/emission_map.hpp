// The adaptive emission map (photon_emission: adaptive-map), in the style of lightweight photon mapping's
// emission guiding: every projection-map component whose two emission numbers the solver maps itself
// (a finite light's cone towards one target; the targets' rectangle or disk of the sun or an
// environment) has a slot, and a slot whose uniform photon paths camera lookups used gets a histogram of
// kSide x kSide cells over the unit square of those numbers. Its density is proportional to where used
// paths started, blurred by one cell and mixed with a defensive uniform share, so no emission number
// ever has zero density. Both sides evaluate it (emitters.hpp inverts a direction or an origin back to
// its numbers), so MIS stays a partition of unity. The histograms change only when a photon pass begins,
// from the flags of the map before it; a slot nobody used keeps the uniform density (1).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include <nimbus/cpp/distribution.hpp>
#include <nimbus/cpp/math.hpp>

#include "path_use.hpp"

namespace nimbus::caustics {

class EmissionMap {
 public:
  static constexpr uint32_t kSide = 16, kCells = kSide * kSide;
  // The uniform share of a learnt density: a used path's neighbourhood is a guess, not a bound.
  static constexpr double kDefensive = 0.25;

  // [main-thread] `slots` components, nothing learnt; adaptive = false leaves every density uniform.
  void configure(uint32_t slots, bool adaptive) {
    adaptive_ = adaptive && slots < (kNoEmissionCell / kCells);
    slots_ = slots;
    index_.assign(adaptive_ ? slots : 0, kNone);
    learnt_.clear(), dists_.clear();
  }
  // Whether slot has a learnt density (else it is 1 everywhere and needs no inversion).
  bool learnt(uint32_t slot) const { return slot < index_.size() && index_[slot] < dists_.size(); }
  size_t slots_learnt() const { return dists_.size(); }

  // [any-thread] Maps (u0, u1), uniform in the unit square, to slot's density; returns the cell code
  // (kNoEmissionCell without adaptation).
  uint32_t warp(uint32_t slot, float &u0, float &u1) const {
    if (!adaptive_ || slot >= slots_) return kNoEmissionCell;
    if (learnt(slot)) {
      float u = 0, v = 0;
      dists_[index_[slot]].sample(u0, u1, u, v, nullptr);
      u0 = u, u1 = v;
    }
    return slot * kCells + cell_of(u0, u1);
  }
  // [any-thread] slot's density at (u0, u1) in the unit square.
  float pdf(uint32_t slot, float u0, float u1) const {
    return learnt(slot) ? dists_[index_[slot]].pdf(clamp01(u0), clamp01(u1)) : 1.0f;
  }

  // [main-thread] A uniform photon path emitted in cell `code` of the current map; used: a lookup used
  // one of its photons. Weighs it by 1 / its density, so that the sum estimates where used paths start
  // whatever density drew them.
  void count(uint32_t code, bool used) {
    if (!adaptive_ || !used || code == kNoEmissionCell) return;
    const uint32_t slot = code / kCells, cell = code % kCells;
    if (slot >= slots_) return;
    if (index_[slot] == kNone) index_[slot] = uint32_t(learnt_.size()), learnt_.push_back({slot, {}});
    const float p = learnt(slot) ? dists_[index_[slot]].cell_pdf(cell) : 1.0f;
    learnt_[index_[slot]].weight[cell] += 1.0 / double(p);
  }
  // [main-thread] The densities of the next map, from everything counted so far.
  void update() {
    dists_.resize(learnt_.size());
    for (size_t i = 0; i < learnt_.size(); ++i) dists_[i] = density(learnt_[i].weight);
  }

  template <class Writer>
  void save(Writer &w) const {
    w.put(uint64_t(learnt_.size()));
    for (const Learnt &l : learnt_) w.put(l.slot), w.put(l.weight);
  }
  // Then update() gives the densities the saved render's current map was traced with.
  template <class Reader>
  bool restore(Reader &r) {
    uint64_t n = 0;
    if (!r.get(n) || n > (adaptive_ ? slots_ : 0)) return false;
    std::vector<uint32_t> index(index_.size(), kNone);
    std::vector<Learnt> learnt(n);
    for (uint64_t i = 0; i < n; ++i) {
      if (!(r.get(learnt[i].slot) && r.get(learnt[i].weight)) || learnt[i].slot >= slots_ ||
          index[learnt[i].slot] != kNone)
        return false;
      for (double x : learnt[i].weight)
        if (!(x >= 0) || !std::isfinite(x)) return false;
      index[learnt[i].slot] = uint32_t(i);
    }
    index_ = std::move(index), learnt_ = std::move(learnt), dists_.clear();
    return true;
  }

 private:
  static constexpr uint32_t kNone = 0xffffffffu;
  struct Learnt {
    uint32_t slot = 0;
    std::array<double, kCells> weight{};
  };

  static float clamp01(float u) { return std::min(std::max(u, 0.0f), 0x1.fffffep-1f); }
  static uint32_t cell_of(float u0, float u1) {
    const uint32_t x = std::min(uint32_t(clamp01(u0) * kSide), kSide - 1);
    const uint32_t y = std::min(uint32_t(clamp01(u1) * kSide), kSide - 1);
    return y * kSide + x;
  }
  // The weights blurred by a 3 x 3 tent (neighbours of a used cell are likely useful too; cells at the
  // square's edge keep their mass), normalised and mixed with the defensive share.
  static Distribution2D density(const std::array<double, kCells> &weight) {
    std::array<double, kCells> blurred{};
    double total = 0;
    for (int y = 0; y < int(kSide); ++y)
      for (int x = 0; x < int(kSide); ++x) {
        double sum = 0, norm = 0;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int nx = x + dx, ny = y + dy;
            if (nx < 0 || ny < 0 || nx >= int(kSide) || ny >= int(kSide)) continue;
            const double k = (2 - std::abs(dx)) * (2 - std::abs(dy));
            sum += k * weight[size_t(ny * int(kSide) + nx)], norm += k;
          }
        blurred[size_t(y * int(kSide) + x)] = sum / norm;
        total += sum / norm;
      }
    std::vector<float> f(kCells);
    for (uint32_t c = 0; c < kCells; ++c)
      f[c] = float((total > 0 ? (1 - kDefensive) * blurred[c] / total : 0.0) + kDefensive / kCells);
    return Distribution2D(f, kSide, kSide);
  }

  bool adaptive_ = false;
  uint32_t slots_ = 0;
  std::vector<uint32_t> index_;        // per slot: its entry in learnt_ (and dists_), or kNone
  std::vector<Learnt> learnt_;         // the slots some used path started in
  std::vector<Distribution2D> dists_;  // their densities, frozen per map
};

}  // namespace nimbus::caustics
