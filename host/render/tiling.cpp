#include "render/tiling.hpp"

#include <algorithm>

namespace nimbus {

Tiling make_tiles(uint32_t w, uint32_t h, const uint32_t reg[4]) {
  const bool has_region = reg[2] > reg[0] && reg[3] > reg[1];
  const uint32_t rx0 = has_region ? std::min(reg[0], w) : 0, ry0 = has_region ? std::min(reg[1], h) : 0;
  const uint32_t rx1 = has_region ? std::min(reg[2], w) : w, ry1 = has_region ? std::min(reg[3], h) : h;
  Tiling t;
  for (uint32_t y = ry0; y < ry1; y += kTileSize)
    for (uint32_t x = rx0; x < rx1; x += kTileSize)
      t.tiles.push_back({x, y, std::min(rx1, x + kTileSize), std::min(ry1, y + kTileSize), 0});
  t.pixels = uint64_t(rx1 - rx0) * (ry1 - ry0);
  return t;
}

}  // namespace nimbus
