// Which photon paths of the current map were used (solver spec 6.1): the light each path of the pass was
// emitted from, its emission-map cell, whether it was a uniform sample (guided proposals are not), and a
// flag a camera lookup sets when one of the path's photons contributed. Light selection counts the
// uniform paths per light, and those used, when the next pass begins (the adaptive emission map the
// used ones per cell); the flags survive a checkpoint so a resumed render counts
// what an uninterrupted one counts.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

namespace nimbus::caustics {

// A path's entry: its light, or kNoLight when it emitted nothing, with kProposalPath set for a guided
// proposal.
inline constexpr uint32_t kNoLight = 0x7fffffffu;
inline constexpr uint32_t kProposalPath = 0x80000000u;
// A path's emission cell (emission_map.hpp: slot * kCells + cell), or kNoEmissionCell when the
// emission map did not place its numbers.
inline constexpr uint32_t kNoEmissionCell = 0xffffffffu;

class PathUse {
 public:
  // [main-thread] The paths of a new map (their lights and emission cells), none used yet.
  void reset(std::vector<uint32_t> lights, std::vector<uint32_t> cells) {
    lights_ = std::move(lights), cells_ = std::move(cells);
    cells_.resize(lights_.size(), kNoEmissionCell);
    used_ = std::make_unique<std::atomic<uint8_t>[]>(lights_.size());
    for (size_t i = 0; i < lights_.size(); ++i) used_[i].store(0, std::memory_order_relaxed);
  }
  // [render-thread] A lookup used a photon of `path`. Relaxed: the flags are read after the camera pass.
  void mark(uint32_t path) {
    if (path >= lights_.size()) return;
    std::atomic<uint8_t> &f = used_[path];
    if (f.load(std::memory_order_relaxed) == 0) f.store(1, std::memory_order_relaxed);
  }
  // [main-thread] f(light, cell, uniform, used) for every path that emitted.
  template <class F>
  void for_each(F &&f) const {
    for (size_t i = 0; i < lights_.size(); ++i) {
      const uint32_t light = lights_[i] & ~kProposalPath;
      if (light != kNoLight)
        f(light, cells_[i], (lights_[i] & kProposalPath) == 0, used_[i].load(std::memory_order_relaxed) != 0);
    }
  }
  size_t size() const { return lights_.size(); }

  // The flags as bits (the lights come back with the map, which a resumed render traces again).
  std::vector<uint64_t> used_bits() const {
    std::vector<uint64_t> bits((lights_.size() + 63) / 64, 0);
    for (size_t i = 0; i < lights_.size(); ++i)
      if (used_[i].load(std::memory_order_relaxed)) bits[i / 64] |= uint64_t(1) << (i % 64);
    return bits;
  }
  // The flags in a render state, and read back (at most 2^26 words) for set_used_bits.
  template <class Writer>
  void save_used(Writer &w) const {
    const std::vector<uint64_t> bits = used_bits();
    w.put(uint64_t(bits.size()));
    for (uint64_t b : bits) w.put(b);
  }
  template <class Reader>
  static bool read_used(Reader &r, std::vector<uint64_t> &bits) {
    uint64_t words = 0;
    if (!r.get(words) || words > (uint64_t(1) << 26)) return false;
    bits.resize(words);
    for (uint64_t &b : bits)
      if (!r.get(b)) return false;
    return true;
  }
  bool set_used_bits(const std::vector<uint64_t> &bits) {
    if (bits.size() != (lights_.size() + 63) / 64) return false;
    for (size_t i = 0; i < lights_.size(); ++i)
      used_[i].store(uint8_t((bits[i / 64] >> (i % 64)) & 1), std::memory_order_relaxed);
    return true;
  }

 private:
  std::vector<uint32_t> lights_;
  std::vector<uint32_t> cells_;
  std::unique_ptr<std::atomic<uint8_t>[]> used_;
};

}  // namespace nimbus::caustics
