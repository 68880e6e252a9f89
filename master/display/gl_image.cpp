#include "display/gl_image.h"

#include <GL/gl.h>

namespace igi {

void draw_srgb8(const std::vector<unsigned char>& rgb, int width, int height) {
  glViewport(0, 0, width, height);
  glClear(GL_COLOR_BUFFER_BIT);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glRasterPos2f(-1.0f, 1.0f);
  glPixelZoom(1.0f, -1.0f);  // image row 0 at the top
  glDrawPixels(width, height, GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
}

Image read_back_buffer(int width, int height) {
  std::vector<unsigned char> rgb(size_t(width) * height * 3);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadBuffer(GL_BACK);
  glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
  Image shot(width, height);  // OpenGL rows run bottom-up
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c)
        shot.at(x, height - 1 - y)[c] = srgb_to_linear(rgb[(size_t(y) * width + x) * 3 + c] / 255.0f);
  return shot;
}

}  // namespace igi
