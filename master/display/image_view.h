#pragma once
// The accumulated image on the GPU: linear floats go up as a texture and a
// fragment shader applies exposure and the sRGB curve (the same formula as
// image/image.cpp's linear_to_srgb), so no thread converts pixels on the CPU.
// GLSL 1.20 on a legacy context: any OpenGL 2.1 driver, Mesa's llvmpipe included.
#include "image/image.h"

namespace igi {

class ImageView {
 public:
  // Needs the window's context current. Throws std::runtime_error when the shader does not build.
  ImageView();
  ~ImageView();
  ImageView(const ImageView&) = delete;
  ImageView& operator=(const ImageView&) = delete;
  // Copies the pixels into the texture (resized on a new size).
  void upload(const Image& image);
  // Fills a width x height viewport with the last upload, image row 0 at the top.
  void draw(int width, int height, float exposure) const;

 private:
  unsigned texture_ = 0, program_ = 0;
  int width_ = 0, height_ = 0;
  int exposure_location_ = -1;
};

}  // namespace igi
