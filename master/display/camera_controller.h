#pragma once
// Fly-through camera: mouse look (yaw, pitch), WASD + Q/E moves, R resets.
// Pure state: the window feeds it input, the master reads `camera()`.
#include "scene/scene.h"

namespace igi {

class CameraController {
 public:
  // `speed`: distance per second, e.g. a fraction of the scene's diagonal.
  CameraController(const Camera& home, float speed);
  // Mouse motion in pixels while the button is held.
  void look(float dx, float dy);
  // Axes in [-1, 1] (forward, right, up), held for `seconds`.
  void move(float forward, float right, float up, float seconds);
  void reset();
  const Camera& camera() const { return camera_; }
  // Bumped by every change: frames rendered with an older generation are stale.
  uint64_t generation() const { return generation_; }

 private:
  void update();
  Camera home_, camera_;
  float yaw_ = 0.0f, pitch_ = 0.0f, speed_;
  glm::vec3 home_forward_, right_;
  uint64_t generation_ = 0;
};

}  // namespace igi
