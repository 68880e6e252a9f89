#pragma once
// The master's window: shows the latest (accumulated) frame, turns keyboard
// and mouse into camera moves, and shows a status line in its title bar.
// The image goes up as floats; the GPU applies exposure and sRGB (image_view.h).
#include <memory>
#include <string>

#include "display/camera_controller.h"
#include "display/image_view.h"
#include "image/image.h"

struct GLFWwindow;

namespace igi {

class InteractiveWindow {
 public:
  // Throws std::runtime_error when no window can be opened.
  InteractiveWindow(int width, int height, const std::string& title);
  ~InteractiveWindow();
  // Handles input since the last call; false once the user closed the window.
  bool poll(CameraController& camera);
  // Draws into the back buffer; present() makes it visible.
  void show(const Image& image, float exposure);
  void upload(const Image& image);  // show() in two steps: upload once, draw as often as needed
  void draw(float exposure);
  // While a panel has the pointer or the keys, they do not move the camera.
  void set_input_captured(bool mouse, bool keyboard) { mouse_captured_ = mouse, keyboard_captured_ = keyboard; }
  GLFWwindow* handle() const { return window_; }
  void present();
  void set_status(const std::string& status);
  // Saves what the window shows (the back buffer) as an image file.
  void screenshot(const std::string& path);

 private:
  GLFWwindow* window_ = nullptr;
  std::string title_;
  double last_time_ = 0.0, last_x_ = 0.0, last_y_ = 0.0;
  bool dragging_ = false, mouse_captured_ = false, keyboard_captured_ = false;
  int width_, height_;
  std::unique_ptr<ImageView> view_;
};

}  // namespace igi
