// Where the camera needs photons (solver spec 6.3): a sparse multi-level voxel hash (an octree without
// the tree) whose cells hold the importance of successful photon lookups. A lookup of radius r that found
// light at x marks the cell of level L = ceil(log2(4 r / h0)) (cell size 2^L h0 >= 4 r, h0 = 1e-6 R_scene)
// containing x with I = 1 / max(l^2, l_min^2), l the camera path length to x; a cell keeps the largest
// mark. I(y) is the largest value over the levels present at y. Camera passes collect marks per worker
// (ImportanceMarks); end_iteration merges them into the render's map, and each photon pass reads a frozen
// copy, so the photons' targets and the camera side's effective photon counts see the same map.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#include <nimbus/cpp/math.hpp>
#include <nimbus/cpp/rng.hpp>

namespace nimbus::caustics {

// A flat open-addressing table from 64-bit cell keys to the largest value given for them. Keys are
// hashes of (level, cell), never 0 (the empty slot). Linear probing, at most half full.
class CellTable {
 public:
  void max_into(uint64_t key, float value) {
    if (2 * (size_ + 1) > keys_.size()) grow();
    const size_t i = slot(key);
    if (keys_[i] == 0)
      keys_[i] = key, values_[i] = value, ++size_;
    else
      values_[i] = std::max(values_[i], value);
  }
  float find(uint64_t key) const {
    if (keys_.empty()) return 0;
    const size_t i = slot(key);
    return keys_[i] == key ? values_[i] : 0.0f;
  }
  size_t size() const { return size_; }
  void clear() { std::fill(keys_.begin(), keys_.end(), 0), size_ = 0; }
  template <class F>
  void for_each(F &&f) const {
    for (size_t i = 0; i < keys_.size(); ++i)
      if (keys_[i] != 0) f(keys_[i], values_[i]);
  }

 private:
  size_t slot(uint64_t key) const {
    const size_t mask = keys_.size() - 1;
    size_t i = size_t(mix64(key)) & mask;
    while (keys_[i] != 0 && keys_[i] != key) i = (i + 1) & mask;
    return i;
  }
  void grow() {
    std::vector<uint64_t> keys = std::move(keys_);
    std::vector<float> values = std::move(values_);
    keys_.assign(std::max<size_t>(64, 2 * keys.size()), 0);
    values_.assign(keys_.size(), 0.0f);
    size_ = 0;
    for (size_t i = 0; i < keys.size(); ++i)
      if (keys[i] != 0) max_into(keys[i], values[i]);
  }
  std::vector<uint64_t> keys_;
  std::vector<float> values_;
  size_t size_ = 0;
};

// The cell geometry shared by marks and queries.
struct CellGrid {
  static constexpr int kLevels = 64;
  float h0 = 1e-6f;  // finest cell size
  Vec3f origin;      // corner of the scene's bounding cube

  CellGrid() = default;
  CellGrid(const Vec3f &center, float radius) : h0(1e-6f * radius), origin(center - Vec3f(radius)) {}

  int level_for(float r) const {
    const float ratio = 4 * r / h0;
    if (!(ratio > 1)) return 0;
    return std::min(kLevels - 1, int(std::ceil(std::log2(ratio))));
  }
  uint64_t key(int level, const Vec3f &p) const {
    const float inv = 1.0f / std::ldexp(h0, level);
    const Vec3f c = (p - origin) * inv;
    const auto cell = [](float v) { return uint64_t(int64_t(std::floor(v))); };
    const uint64_t k = hash_keys({uint64_t(level), cell(c.x), cell(c.y), cell(c.z)});
    return k == 0 ? 1 : k;
  }
};

// One worker's marks since the last merge.
class ImportanceMarks {
 public:
  void add(const CellGrid &grid, const Vec3f &p, float radius, float importance) {
    const int level = grid.level_for(radius);
    cells_.max_into(grid.key(level, p), importance);
    levels_ |= uint64_t(1) << level;
  }
  const CellTable &cells() const { return cells_; }
  uint64_t levels() const { return levels_; }
  void clear() { cells_.clear(), levels_ = 0; }

 private:
  CellTable cells_;
  uint64_t levels_ = 0;
};

class ImportanceMap {
 public:
  ImportanceMap() = default;
  // scene_center, scene_radius: the scene's bounding sphere (h0 and the shortest path length follow it).
  ImportanceMap(const Vec3f &scene_center, float scene_radius)
      : grid_(scene_center, scene_radius), l_min_(1e-3f * scene_radius) {}

  // The mark of a lookup at path length `length`.
  float importance(float length) const {
    const float l = std::max(length, l_min_);
    return 1.0f / (l * l);
  }
  const CellGrid &grid() const { return grid_; }

  // [main-thread] Folds a worker's marks in (cells keep the largest value) and empties them.
  void merge(ImportanceMarks &marks) {
    marks.cells().for_each([&](uint64_t k, float v) { cells_.max_into(k, v); });
    levels_ |= marks.levels();
    marks.clear();
  }
  bool empty() const { return cells_.size() == 0; }
  size_t cells() const { return cells_.size(); }

  // [any-thread, read-only] I(p): the largest value over the levels present.
  float at(const Vec3f &p) const {
    float best = 0;
    for (uint64_t l = levels_; l != 0; l &= l - 1) {
      const int level = std::countr_zero(l);
      best = std::max(best, cells_.find(grid_.key(level, p)));
    }
    return best;
  }

  // The marks, for a resumed render (sdk::StateWriter and sdk::StateReader); restore changes nothing
  // unless it reads all of it.
  template <class Writer>
  void save(Writer &w) const {
    w.put(levels_), w.put(uint64_t(cells_.size()));
    cells_.for_each([&](uint64_t k, float v) { w.put(k), w.put(v); });
  }
  template <class Reader>
  bool restore(Reader &r) {
    uint64_t levels = 0, n = 0;
    if (!(r.get(levels) && r.get(n))) return false;
    CellTable cells;
    for (uint64_t i = 0; i < n; ++i) {
      uint64_t key = 0;
      float value = 0;
      if (!(r.get(key) && r.get(value)) || key == 0 || !(value >= 0) || !std::isfinite(value)) return false;
      cells.max_into(key, value);
    }
    cells_ = std::move(cells), levels_ = levels;
    return true;
  }

 private:
  CellGrid grid_;
  float l_min_ = 1e-3f;
  CellTable cells_;
  uint64_t levels_ = 0;  // bit L: some cell of level L is marked
};

}  // namespace nimbus::caustics
