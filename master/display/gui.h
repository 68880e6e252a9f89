#pragma once
// Dear ImGui in the master's window: its context and its GLFW and OpenGL 2
// backends (Debian's libimgui-dev builds them into libimgui.a). The OpenGL 2
// backend draws with the legacy pipeline the window already uses, so Mesa's
// llvmpipe under Xvfb runs it.
struct GLFWwindow;

namespace igi {

class Gui {
 public:
  // Installs ImGui's GLFW callbacks; they call any callbacks set before them.
  explicit Gui(GLFWwindow* window);
  ~Gui();
  Gui(const Gui&) = delete;
  Gui& operator=(const Gui&) = delete;
  void begin_frame();
  // Draws what the panels built since begin_frame() into the back buffer.
  void render();
  // The pointer is over a panel, or a text field has the keys: the camera must not move.
  bool wants_mouse() const;
  bool wants_keyboard() const;
};

}  // namespace igi
