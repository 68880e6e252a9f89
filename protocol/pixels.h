#pragma once
// Tile pixels on their way onto and off the wire.
//
// Worker side: wire_pixels() makes a rendered tile sendable: a pixel with a
// NaN or infinite channel becomes black (the decoder rejects non-finite
// pixels, so one bad sample would otherwise lose the whole tile on every
// worker alike), and as half floats each channel is clamped to +-65504.
//
// Master side: copy_tile_pixels() moves a decoded TileResultView's pixels
// straight from the received ZeroMQ frame into the frame buffer, row by row,
// checking that every value is finite as it goes.
#include <cstdint>
#include <span>
#include <string>

#include <glm/glm.hpp>

#include "protocol/codec.h"

namespace igi::protocol {

// Returns how many pixels were non-finite (now zero).
uint32_t wire_pixels(std::span<glm::vec3> pixels, PixelFormat format);

// dst: where the tile's top-left pixel goes; dst_row_bytes: the destination's
// pitch (the frame's row). The destination must have the view's pixel format.
// Returns "" or, for a non-finite value, the very error decode() gives for the
// same bytes; the rows copied by then are garbage the caller must not use.
std::string copy_tile_pixels(const TileResultView& view, uint8_t* dst, size_t dst_row_bytes);

// The view's surfaces (decode_tile_result checked them), to `dst`: the
// surface of the tile's top-left pixel in a frame `dst_row_pixels` wide.
// The view must have surfaces.
void copy_tile_surfaces(const TileResultView& view, PixelSurface* dst, size_t dst_row_pixels);

}  // namespace igi::protocol
