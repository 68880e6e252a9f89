#pragma once
// The accumulated image on the GPU: linear floats go up as a texture, and a
// fragment shader multiplies them by the exposure and looks the view
// transform up in a 3-D table sampled from image/view_transform.h's function
// (view_table(): the function every 8-bit output uses, so no second copy of
// it lives in GLSL), so no thread converts pixels on the CPU. The image goes
// into a viewport of the window (display/panel_layout.h), the rest of the
// window a dark surround. GLSL 1.20 on a legacy context: any OpenGL 2.1
// driver, Mesa's llvmpipe included.
#include <vector>

#include "display/panel_layout.h"
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
  // Display pixels as they are (8-bit sRGB, three bytes each, row 0 at the
  // top: a remote master tone-mapped them, viewer/): drawn with no exposure or
  // view transform until the next upload(Image).
  void upload_srgb8(const std::vector<unsigned char>& rgb, int width, int height);
  // Draws the last upload into `where` of a window_width x window_height back
  // buffer, image row 0 at the top, through `tone`: a new view's table is
  // built (about 0.5 M samples of the function) and uploaded first.
  void draw(int window_width, int window_height, const Viewport& where, const ToneMapping& tone);

 private:
  unsigned texture_ = 0, table_ = 0, program_ = 0, plain_program_ = 0;
  int width_ = 0, height_ = 0;
  bool srgb8_ = false;  // the texture holds display pixels: drawn by plain_program_
  int exposure_location_ = -1;
  bool table_built_ = false;
  ViewTransform view_ = ViewTransform::Standard;
};

}  // namespace igi
