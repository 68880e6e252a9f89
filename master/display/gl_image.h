#pragma once
// The two things both windows do with OpenGL (legacy, so Mesa's llvmpipe under
// Xvfb runs it): draw an image over the viewport, and read back what it shows.
#include <vector>

#include "image/image.h"

namespace igi {

// 8-bit sRGB pixels, three bytes each, row 0 at the top, drawn into the back buffer.
void draw_srgb8(const std::vector<unsigned char>& rgb, int width, int height);
// The back buffer as an image (the front buffer reads as zeros under Xvfb).
Image read_back_buffer(int width, int height);

}  // namespace igi
