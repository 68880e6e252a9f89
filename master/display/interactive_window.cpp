#include "display/interactive_window.h"

#include <stdexcept>
#include <vector>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "display/gl_image.h"

namespace igi {

InteractiveWindow::InteractiveWindow(int width, int height, const std::string& title)
    : title_(title), width_(width), height_(height) {
  if (glfwInit() != GLFW_TRUE) throw std::runtime_error("cannot start GLFW (no display?)");
  glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);
  window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (!window_) {
    glfwTerminate();
    throw std::runtime_error("cannot open a window");
  }
  glfwMakeContextCurrent(window_);
  glfwSwapInterval(0);
  last_time_ = glfwGetTime();
  try {
    view_ = std::make_unique<ImageView>();
  } catch (...) {
    glfwDestroyWindow(window_);
    glfwTerminate();
    throw;
  }
}

InteractiveWindow::~InteractiveWindow() {
  view_.reset();  // its GL objects go while the context lives
  glfwDestroyWindow(window_);
  glfwTerminate();
}

bool InteractiveWindow::poll(CameraController& camera) {
  glfwPollEvents();
  const double now = glfwGetTime(), dt = now - last_time_;
  last_time_ = now;
  auto key = [&](int k) { return !keyboard_captured_ && glfwGetKey(window_, k) == GLFW_PRESS ? 1.0f : 0.0f; };
  if (key(GLFW_KEY_ESCAPE)) glfwSetWindowShouldClose(window_, GLFW_TRUE);
  if (key(GLFW_KEY_R)) camera.reset();
  camera.move(key(GLFW_KEY_W) - key(GLFW_KEY_S), key(GLFW_KEY_D) - key(GLFW_KEY_A), key(GLFW_KEY_E) - key(GLFW_KEY_Q),
              float(dt));
  camera.move_lights(key(GLFW_KEY_L) - key(GLFW_KEY_J), key(GLFW_KEY_O) - key(GLFW_KEY_U),
                     key(GLFW_KEY_K) - key(GLFW_KEY_I), float(dt));
  double x, y;
  glfwGetCursorPos(window_, &x, &y);
  const bool pressed = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS && (dragging_ || !mouse_captured_);
  if (pressed && dragging_) camera.look(float(x - last_x_), float(y - last_y_));
  dragging_ = pressed;
  last_x_ = x;
  last_y_ = y;
  return !glfwWindowShouldClose(window_);
}

void InteractiveWindow::show(const Image& image, float exposure) {
  upload(image);
  draw(exposure);
}

void InteractiveWindow::upload(const Image& image) { view_->upload(image); }

void InteractiveWindow::draw(float exposure) { view_->draw(width_, height_, exposure); }

void InteractiveWindow::present() { glfwSwapBuffers(window_); }

void InteractiveWindow::set_status(const std::string& status) {
  glfwSetWindowTitle(window_, (title_ + "  |  " + status).c_str());
}

void InteractiveWindow::screenshot(const std::string& path) { write_image(read_back_buffer(width_, height_), path); }

}  // namespace igi
