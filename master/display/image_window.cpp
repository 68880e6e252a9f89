#include "display/image_window.h"

#include <cstdlib>
#include <stdexcept>
#include <vector>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <GL/gl.h>

namespace igi {
namespace {

struct Glfw {
  bool ok = glfwInit() == GLFW_TRUE;
  ~Glfw() { if (ok) glfwTerminate(); }
};

// Reads the back buffer (the front buffer reads as zeros under Xvfb).
void save_screenshot(int width, int height, const std::string& path) {
  std::vector<unsigned char> rgb(size_t(width) * height * 3);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadBuffer(GL_BACK);
  glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
  Image shot(width, height);  // OpenGL rows run bottom-up
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c)
        shot.at(x, height - 1 - y)[c] = srgb_to_linear(rgb[(size_t(y) * width + x) * 3 + c] / 255.0f);
  write_image(shot, path);
}

}  // namespace

bool window_available() {
  const char* display = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  if ((!display || !*display) && (!wayland || !*wayland)) return false;
  Glfw glfw;
  return glfw.ok;
}

void show_image(const Image& image, const WindowOptions& options) {
  Glfw glfw;
  if (!glfw.ok) throw std::runtime_error("cannot start GLFW (no display?)");
  glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);
  GLFWwindow* window = glfwCreateWindow(image.width, image.height, options.title.c_str(), nullptr, nullptr);
  if (!window) throw std::runtime_error("cannot open a window");
  glfwMakeContextCurrent(window);
  const std::vector<unsigned char> rgb = to_srgb8(image, options.exposure);
  const double start = glfwGetTime();
  while (!glfwWindowShouldClose(window)) {
    int fb_w, fb_h;
    glfwGetFramebufferSize(window, &fb_w, &fb_h);
    glViewport(0, 0, fb_w, fb_h);
    glClear(GL_COLOR_BUFFER_BIT);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glRasterPos2f(-1.0f, 1.0f);
    glPixelZoom(1.0f, -1.0f);  // image row 0 at the top
    glDrawPixels(image.width, image.height, GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
    if (!options.screenshot.empty()) {
      save_screenshot(fb_w, fb_h, options.screenshot);
      break;
    }
    glfwSwapBuffers(window);
    glfwWaitEventsTimeout(0.1);
    if (glfwGetKey(window, GLFW_KEY_ESCAPE) == GLFW_PRESS) break;
    if (options.seconds > 0.0 && glfwGetTime() - start > options.seconds) break;
  }
  glfwDestroyWindow(window);
}

}  // namespace igi
