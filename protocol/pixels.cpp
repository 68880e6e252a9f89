#include "protocol/pixels.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "image/half.h"

namespace igi::protocol {

uint32_t wire_pixels(std::span<glm::vec3> pixels, PixelFormat format) {
  uint32_t nonfinite = 0;
  for (glm::vec3& p : pixels)
    if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z))) {
      p = glm::vec3(0.0f);
      ++nonfinite;
    }
  if (format == PixelFormat::Float16)
    for (glm::vec3& p : pixels) p = glm::clamp(p, glm::vec3(-kHalfMax), glm::vec3(kHalfMax));
  // Rgb9e5: its encoding clamps to [0, kRgb9e5Max] itself.
  return nonfinite;
}

namespace {

// True when any of the n values has an all-ones exponent (infinity or NaN).
// A shared-exponent word has no such value: every word is a finite colour.
bool any_nonfinite(const uint8_t* bytes, size_t n, PixelFormat format) {
  uint32_t bad = 0;
  if (format == PixelFormat::Float16) {
    for (size_t i = 0; i < n; ++i) {
      uint16_t v;
      std::memcpy(&v, bytes + 2 * i, 2);
      bad |= uint32_t((v & 0x7c00u) == 0x7c00u);
    }
  } else if (format == PixelFormat::Float32) {
    for (size_t i = 0; i < n; ++i) {
      uint32_t v;
      std::memcpy(&v, bytes + 4 * i, 4);
      bad |= uint32_t((v & 0x7f800000u) == 0x7f800000u);
    }
  }
  return bad != 0;
}

// Pixel i of a block of halves or floats.
glm::vec3 pixel_at(const uint8_t* bytes, size_t i, PixelFormat format) {
  glm::vec3 p;
  if (format == PixelFormat::Float16) {
    uint16_t v[3];
    std::memcpy(v, bytes + 6 * i, 6);
    return {from_half(v[0]), from_half(v[1]), from_half(v[2])};
  }
  std::memcpy(&p, bytes + 12 * i, 12);
  return p;
}

// decode()'s words for the first non-finite pixel of the block.
std::string nonfinite_error(std::span<const uint8_t> block, PixelFormat format) {
  for (size_t i = 0, n = block.size() / bytes_per_pixel(format); i < n; ++i) {
    const glm::vec3 p = pixel_at(block.data(), i, format);
    if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) continue;
    char text[160];
    std::snprintf(text, sizeof text, "TileResult.pixels: pixel %zu is (%.9g, %.9g, %.9g), expected finite values", i,
                  double(p.x), double(p.y), double(p.z));
    return text;
  }
  return "TileResult.pixels: a non-finite value";  // not reached: the caller saw one
}

}  // namespace

std::string copy_tile_pixels(const TileResultView& view, uint8_t* dst, size_t dst_row_bytes) {
  const PixelFormat format = view.fields.pixel_format;
  const size_t row_bytes = size_t(view.fields.tile.w) * bytes_per_pixel(format);
  const size_t row_values = size_t(view.fields.tile.w) * 3;  // halves or floats (no shared-exponent word is non-finite)
  for (int y = 0; y < view.fields.tile.h; ++y) {
    uint8_t* row = dst + size_t(y) * dst_row_bytes;
    std::memcpy(row, view.pixel_bytes.data() + size_t(y) * row_bytes, row_bytes);
    if (any_nonfinite(row, row_values, format)) return nonfinite_error(view.pixel_bytes, format);
  }
  return {};
}

void copy_tile_surfaces(const TileResultView& view, PixelSurface* dst, size_t dst_row_pixels) {
  const int w = view.fields.tile.w;
  const uint8_t* bytes = view.surface_bytes.data();
  for (int y = 0; y < view.fields.tile.h; ++y)
    for (int x = 0; x < w; ++x, bytes += 8) {
      PixelSurface& s = dst[size_t(y) * dst_row_pixels + size_t(x)];
      std::memcpy(&s.depth, bytes, 4);  // little-endian on the wire and on every machine this builds for
      for (int k = 0; k < 3; ++k) s.normal[k] = static_cast<int8_t>(bytes[4 + k]);
      s.flags = bytes[7];
    }
}

}  // namespace igi::protocol
