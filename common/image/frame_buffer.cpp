#include "image/frame_buffer.h"

#include <cstring>

#include "image/half.h"
#include "image/rgb9e5.h"

namespace igi {

const char* pixel_format_name(PixelFormat format) {
  switch (format) {
    case PixelFormat::Float32: return "float";
    case PixelFormat::Float16: return "half";
    case PixelFormat::Rgb9e5: return "rgb9e5";
  }
  return "unknown";
}

Image FrameBuffer::to_image() const {
  Image image(width, height);
  const size_t values = size_t(width) * size_t(height) * 3;
  float* out = &image.pixels.data()->x;
  switch (format) {
    case PixelFormat::Float32: std::memcpy(out, bytes.data(), values * sizeof(float)); break;
    case PixelFormat::Float16: from_half(reinterpret_cast<const uint16_t*>(bytes.data()), out, values); break;
    case PixelFormat::Rgb9e5: from_rgb9e5(reinterpret_cast<const uint32_t*>(bytes.data()), out, values / 3); break;
  }
  return image;
}

}  // namespace igi
