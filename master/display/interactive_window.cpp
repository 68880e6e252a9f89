#include "display/interactive_window.h"

#include <stdexcept>
#include <utility>
#include <vector>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "display/gl_image.h"

namespace igi {

namespace {

// The width of the primary monitor's work area (no panels or docks), or of its mode.
int screen_width() {
  GLFWmonitor* monitor = glfwGetPrimaryMonitor();
  if (!monitor) return 0;
  int x = 0, y = 0, width = 0, height = 0;
  glfwGetMonitorWorkarea(monitor, &x, &y, &width, &height);
  if (width > 0) return width;
  const GLFWvidmode* mode = glfwGetVideoMode(monitor);
  return mode ? mode->width : 0;
}

}  // namespace

InteractiveWindow::InteractiveWindow(int image_width, int image_height, float panel_width, bool panel_shown,
                                     const std::string& title)
    : title_(title), height_(image_height) {
  if (glfwInit() != GLFW_TRUE) throw std::runtime_error("cannot start GLFW (no display?)");
  width_ = window_width(image_width, panel_width, panel_shown, screen_width());
  glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);
  window_ = glfwCreateWindow(width_, height_, title.c_str(), nullptr, nullptr);
  if (!window_) {
    glfwTerminate();
    throw std::runtime_error("cannot open a window");
  }
  glfwMakeContextCurrent(window_);
  glfwSwapInterval(0);
  last_time_ = glfwGetTime();
  glfwGetCursorPos(window_, &last_x_, &last_y_);
  // Set before the panel's (gui.cpp), which calls these after its own.
  glfwSetWindowUserPointer(window_, this);
  glfwSetKeyCallback(window_, on_key);
  glfwSetMouseButtonCallback(window_, on_button);
  glfwSetCursorPosCallback(window_, on_cursor);
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

void InteractiveWindow::on_key(GLFWwindow* window, int key, int, int action, int mods) {
  auto* self = static_cast<InteractiveWindow*>(glfwGetWindowUserPointer(window));
  if (action == GLFW_PRESS && !self->keyboard_captured_) {
    self->held_.insert(key);
    self->tapped_.insert(key);
    self->panel_taps_.insert(mods & GLFW_MOD_SHIFT ? key | kShifted : key);
  } else if (action == GLFW_RELEASE) {
    self->held_.erase(key);
  }
}

void InteractiveWindow::on_button(GLFWwindow* window, int button, int action, int) {
  auto* self = static_cast<InteractiveWindow*>(glfwGetWindowUserPointer(window));
  if (button != GLFW_MOUSE_BUTTON_LEFT) return;
  if (action == GLFW_PRESS) self->dragging_ = !self->mouse_captured_;  // a press on the panel is the panel's
  else if (action == GLFW_RELEASE) self->dragging_ = false;
}

void InteractiveWindow::on_cursor(GLFWwindow* window, double x, double y) {
  auto* self = static_cast<InteractiveWindow*>(glfwGetWindowUserPointer(window));
  if (self->dragging_) {
    self->look_x_ += x - self->last_x_;
    self->look_y_ += y - self->last_y_;
  }
  self->last_x_ = x;
  self->last_y_ = y;
}

float InteractiveWindow::axis(int plus, int minus) const {
  auto down = [&](int key) { return held_.count(key) || tapped_.count(key) ? 1.0f : 0.0f; };
  return down(plus) - down(minus);
}

bool InteractiveWindow::poll(CameraController& camera) {
  glfwPollEvents();
  const double now = glfwGetTime(), dt = now - last_time_;
  last_time_ = now;
  if (keyboard_captured_) held_.clear();  // the panel took the keys: nothing stays held behind its back
  if (tapped_.count(GLFW_KEY_ESCAPE)) glfwSetWindowShouldClose(window_, GLFW_TRUE);
  if (tapped_.count(GLFW_KEY_R)) camera.reset();
  camera.move(axis(GLFW_KEY_W, GLFW_KEY_S), axis(GLFW_KEY_D, GLFW_KEY_A), axis(GLFW_KEY_E, GLFW_KEY_Q), float(dt));
  camera.move_lights(axis(GLFW_KEY_L, GLFW_KEY_J), axis(GLFW_KEY_O, GLFW_KEY_U), axis(GLFW_KEY_K, GLFW_KEY_I),
                     float(dt));
  if (look_x_ != 0.0 || look_y_ != 0.0) camera.look(float(look_x_), float(look_y_));
  look_x_ = look_y_ = 0.0;
  tapped_.clear();
  return !glfwWindowShouldClose(window_);
}

std::set<int> InteractiveWindow::take_panel_taps() { return std::exchange(panel_taps_, {}); }

void InteractiveWindow::upload(const Image& image) { view_->upload(image); }

void InteractiveWindow::upload_srgb8(const std::vector<unsigned char>& rgb, int width, int height) {
  view_->upload_srgb8(rgb, width, height);
}

void InteractiveWindow::draw(const Viewport& where, const ToneMapping& tone) {
  view_->draw(width_, height_, where, tone);
}

void InteractiveWindow::present() { glfwSwapBuffers(window_); }

void InteractiveWindow::set_status(const std::string& status) {
  glfwSetWindowTitle(window_, (title_ + "  |  " + status).c_str());
}

void InteractiveWindow::screenshot(const std::string& path) { write_image(read_back_buffer(width_, height_), path); }

}  // namespace igi
