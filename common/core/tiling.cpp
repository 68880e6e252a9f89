#include "core/tiling.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace igi {

std::vector<TileJob> make_tiles(int width, int height, int tile_w, int tile_h, int border) {
  std::vector<TileJob> tiles;
  for (int y = 0; y < height; y += tile_h)
    for (int x = 0; x < width; x += tile_w)
      tiles.push_back({x, y, std::min(tile_w, width - x), std::min(tile_h, height - y), border});
  // Spiral from the centre: order by distance to it, ties by angle (stable).
  const float cx = 0.5f * width, cy = 0.5f * height;
  auto key = [&](const TileJob& t) {
    float dx = t.x + 0.5f * t.w - cx, dy = t.y + 0.5f * t.h - cy;
    return std::make_pair(std::max(std::abs(dx) / tile_w, std::abs(dy) / tile_h), std::atan2(dy, dx));
  };
  std::stable_sort(tiles.begin(), tiles.end(), [&](const TileJob& a, const TileJob& b) { return key(a) < key(b); });
  return tiles;
}

}  // namespace igi
