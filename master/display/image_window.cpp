#include "display/image_window.h"

#include <stdexcept>
#include <vector>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "display/gl_image.h"

namespace igi {
namespace {

struct Glfw {
  bool ok = glfwInit() == GLFW_TRUE;
  ~Glfw() { if (ok) glfwTerminate(); }
};

}  // namespace

void show_image(const Image& image, const WindowOptions& options) {
  Glfw glfw;
  if (!glfw.ok) throw std::runtime_error("cannot start GLFW (no display?)");
  glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);
  GLFWwindow* window = glfwCreateWindow(image.width, image.height, options.title.c_str(), nullptr, nullptr);
  if (!window) throw std::runtime_error("cannot open a window");
  glfwMakeContextCurrent(window);
  const std::vector<unsigned char> rgb = to_srgb8(image, options.tone);
  const double start = glfwGetTime();
  while (!glfwWindowShouldClose(window)) {
    draw_srgb8(rgb, image.width, image.height);
    if (!options.screenshot.empty()) {
      write_image(read_back_buffer(image.width, image.height), options.screenshot);
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
