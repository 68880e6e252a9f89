#pragma once
// One frame's pixels in the format they travel in: three floats, three
// halves or one shared-exponent word per pixel, row-major, row 0 at the top.
// The master assembles tiles straight into it (no conversion on its session
// thread); whoever shows or writes the frame converts it with to_image().
#include <cstddef>
#include <cstdint>
#include <vector>

#include "image/image.h"

namespace igi {

enum class PixelFormat : uint8_t {
  Float32 = 0,  // 12 bytes a pixel: what EXR files and bit-for-bit comparisons need
  Float16 = 1,  // 6 bytes a pixel: display frames (PNG, the window); 11 bits of precision, at most 65504
  Rgb9e5 = 2,   // 4 bytes a pixel: display frames over slow links (image/rgb9e5.h); 9 bits, 0 to 65408
};

const char* pixel_format_name(PixelFormat format);
inline size_t bytes_per_pixel(PixelFormat format) {
  return format == PixelFormat::Float32 ? 12 : format == PixelFormat::Float16 ? 6 : 4;
}

struct FrameBuffer {
  int width = 0, height = 0;
  PixelFormat format = PixelFormat::Float32;
  std::vector<uint8_t> bytes;  // width * height * bytes_per_pixel(format)

  FrameBuffer() = default;
  FrameBuffer(int w, int h, PixelFormat f)
      : width(w), height(h), format(f), bytes(size_t(w) * size_t(h) * bytes_per_pixel(f)) {}
  size_t row_bytes() const { return size_t(width) * bytes_per_pixel(format); }
  uint8_t* pixel(int x, int y) { return bytes.data() + size_t(y) * row_bytes() + size_t(x) * bytes_per_pixel(format); }
  // Linear float RGB (exact for every format).
  Image to_image() const;
};

}  // namespace igi
