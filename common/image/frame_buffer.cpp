#include "image/frame_buffer.h"

#include <cstring>

#include "image/half.h"

namespace igi {

const char* pixel_format_name(PixelFormat format) {
  switch (format) {
    case PixelFormat::Float32: return "float";
    case PixelFormat::Float16: return "half";
  }
  return "unknown";
}

Image FrameBuffer::to_image() const {
  Image image(width, height);
  const size_t values = size_t(width) * size_t(height) * 3;
  float* out = &image.pixels.data()->x;
  if (format == PixelFormat::Float16) from_half(reinterpret_cast<const uint16_t*>(bytes.data()), out, values);
  else std::memcpy(out, bytes.data(), values * sizeof(float));
  return image;
}

}  // namespace igi
