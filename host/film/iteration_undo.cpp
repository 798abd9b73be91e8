#include "film/iteration_undo.hpp"

#include <algorithm>

namespace nimbus {

IterationUndo::IterationUndo(const Film &film) : width_(film.width()) {
  for (int32_t el : film.active_elements())
    saved_.push_back({el, film.element_channels(el), std::vector<double>(film.sums(el).size())});
}

void IterationUndo::save(const Film &film, const nimbus_tile_t &tile) {
  for (Saved &s : saved_) {
    const std::span<const double> from = film.sums(s.element);
    const size_t row = size_t(tile.x1 - tile.x0) * s.channels;
    for (uint32_t y = tile.y0; y < tile.y1; ++y) {
      const size_t at = (size_t(y) * width_ + tile.x0) * s.channels;
      std::copy_n(from.begin() + at, row, s.sums.begin() + at);
    }
  }
}

void IterationUndo::restore(Film &film, const nimbus_tile_t &tile) const {
  for (const Saved &s : saved_) {
    const std::span<double> to = film.sums(s.element);
    const size_t row = size_t(tile.x1 - tile.x0) * s.channels;
    for (uint32_t y = tile.y0; y < tile.y1; ++y) {
      const size_t at = (size_t(y) * width_ + tile.x0) * s.channels;
      std::copy_n(s.sums.begin() + at, row, to.begin() + at);
    }
  }
}

size_t IterationUndo::bytes() const {
  size_t n = 0;
  for (const Saved &s : saved_) n += s.sums.size() * sizeof(double);
  return n;
}

}  // namespace nimbus
