// The undo of one iteration's accumulated samples. Before a tile is rendered its worker copies the tile's
// sums here; if a plugin fails inside the iteration (a hook returns an error, or hangs past the time
// budget), the tiles it had started are copied back, so the film holds exactly the iterations before it
// and the written image is the one those iterations make, with their sample count in its header. The
// cost is one copy of the film's sums, written tile by tile while the tile is in the worker's cache.
#pragma once

#include <cstdint>
#include <vector>

#include <nimbus/integrator.h>

#include "film/film.hpp"

namespace nimbus {

class IterationUndo {
 public:
  // Buffers for the elements active in `film` (call after the film is allocated).
  explicit IterationUndo(const Film &film);

  // [render-thread] Copies the sums of `tile`'s pixels; tiles of one iteration are disjoint.
  void save(const Film &film, const nimbus_tile_t &tile);
  // [main-thread, or a rescuing thread once no tile starts] Puts the saved sums of `tile` back into `film`
  // (the film itself or a snapshot of it).
  void restore(Film &film, const nimbus_tile_t &tile) const;
  // Bytes held, for the memory report.
  size_t bytes() const;

 private:
  struct Saved {
    int32_t element;
    uint32_t channels;
    std::vector<double> sums;
  };
  uint32_t width_;
  std::vector<Saved> saved_;
};

}  // namespace nimbus
