#pragma once
// The master's window: shows the latest (accumulated) frame, turns keyboard
// and mouse into camera moves, and shows a status line in its title bar.
// Input is read as events (GLFW callbacks), not as the state at each poll:
// a key pressed and released between two polls still moves the camera for
// one poll, a drag turns the camera by every motion the cursor made, and a
// press that lands on the panel never turns it, wherever the drag goes.
// The image goes up as floats; the GPU applies the tone mapping (image_view.h).
// The window is the image's size, and wider by the panel's column when the
// panel opens at the start and the screen has room for both (panel_layout.h).
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "display/camera_controller.h"
#include "display/image_view.h"
#include "image/image.h"

struct GLFWwindow;

namespace igi {

class InteractiveWindow {
 public:
  // For an image of image_width x image_height and a panel of panel_width
  // that opens at the start or not. Throws std::runtime_error when no window can be opened.
  InteractiveWindow(int image_width, int image_height, float panel_width, bool panel_shown, const std::string& title);
  ~InteractiveWindow();
  // Handles input since the last call; false once the user closed the window.
  bool poll(CameraController& camera);
  // Draws the last upload into `where` of the back buffer (image_viewport()); present() makes it visible.
  void upload(const Image& image);
  // Display pixels a remote master tone-mapped (igi-view): drawn as they are (ImageView::upload_srgb8).
  void upload_srgb8(const std::vector<unsigned char>& rgb, int width, int height);
  void draw(const Viewport& where, const ToneMapping& tone);
  int width() const { return width_; }
  int height() const { return height_; }
  // While a panel has the pointer or the keys, they do not move the camera.
  void set_input_captured(bool mouse, bool keyboard) { mouse_captured_ = mouse, keyboard_captured_ = keyboard; }
  GLFWwindow* handle() const { return window_; }
  void present();
  void set_status(const std::string& status);
  // Saves what the window shows (the back buffer) as an image file.
  void screenshot(const std::string& path);
  // The keys pressed since the last call, for the panel (which draws less
  // often than events come: a tap between two of its frames is not lost).
  // A key pressed with Shift is key | kShifted.
  static constexpr int kShifted = 1 << 16;
  std::set<int> take_panel_taps();

 private:
  static void on_key(GLFWwindow* window, int key, int scancode, int action, int mods);
  static void on_button(GLFWwindow* window, int button, int action, int mods);
  static void on_cursor(GLFWwindow* window, double x, double y);
  float axis(int plus, int minus) const;  // -1, 0 or 1 from two keys

  GLFWwindow* window_ = nullptr;
  std::string title_;
  double last_time_ = 0.0, last_x_ = 0.0, last_y_ = 0.0;
  double look_x_ = 0.0, look_y_ = 0.0;  // cursor motion while dragging, since the last poll
  std::set<int> held_, tapped_;         // keys down now; keys pressed since the last poll
  std::set<int> panel_taps_;            // keys pressed since the panel last took them
  bool dragging_ = false, mouse_captured_ = false, keyboard_captured_ = false;
  int width_, height_;  // the window's
  std::unique_ptr<ImageView> view_;
};

}  // namespace igi
