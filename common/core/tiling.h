#pragma once
// How a frame is cut into tile jobs, for every renderer alike: the master's
// frames, igi-render's, the tests'. A tile's pixels do not depend on the cut
// (tiles read `border` extra pixels where a method's filter needs them), so
// whole, tiled and distributed renders are equal bit for bit.
#include <vector>

#include "core/frame.h"
#include "core/settings.h"

namespace igi {

// Extra pixels around a tile that the method needs to read: the
// discontinuity buffer's two passes of its window (filter/discontinuity_buffer.h,
// filter_tent), and around it the wavelet filter's footprint. With light on
// a lattice (--light-divisor) that border is the lattice's, which the method
// finds itself (methods/light_upsample.h): the tile needs none.
inline int light_border(const RenderSettings& s) {
  const bool vpl = s.method == MethodKind::Igi || s.method == MethodKind::InstantRadiosity;
  return (s.method == MethodKind::Igi && s.filter ? 2 * (s.interleave / 2) : 0) +
         (vpl ? wavelet_footprint(s.wavelet_levels) : 0);
}
inline bool lattice_light(const RenderSettings& s) {
  return s.light_divisor > 1 && (s.method == MethodKind::Igi || s.method == MethodKind::InstantRadiosity);
}
inline int tile_border(const RenderSettings& s) { return lattice_light(s) ? 0 : light_border(s); }
// With lattice light, tiles are larger by a quarter of the divisor: a tile
// shades the lattice cells around it and their filter border, whose cost
// small tiles pay over and over (at light 1/8, 64-pixel tiles shaded 8.8
// times the lattice's samples), while a frame of a few large tiles leaves
// the master all their pixels to decode at once at the end.
inline int frame_tile_size(int tile_size, const RenderSettings& s) {
  return lattice_light(s) ? tile_size * (4 + s.light_divisor) / 4 : tile_size;
}

// Tiles of at most tile_w x tile_h covering the image, each with `border`,
// ordered in a spiral from the centre so the image fills in evenly.
std::vector<TileJob> make_tiles(int width, int height, int tile_w, int tile_h, int border);

}  // namespace igi
