// The tiles of one render: the render region (the whole image when none is set) cut into kTileSize
// squares in row-major order, clipped at the region's edge. Each tile is rendered by one worker per
// iteration, so tiles never share a pixel.
#pragma once

#include <nimbus/integrator.h>

#include <cstdint>
#include <vector>

namespace nimbus {

inline constexpr uint32_t kTileSize = 32;

struct Tiling {
  std::vector<nimbus_tile_t> tiles;  // iteration 0; the loop sets each tile's iteration
  uint64_t pixels = 0;               // in the region
};

// `region` as RenderDesc::region: [x0, y0, x1, y1], all zero for the whole width x height image.
Tiling make_tiles(uint32_t width, uint32_t height, const uint32_t region[4]);

}  // namespace nimbus
