#pragma once
// Fly-through camera: mouse look (yaw, pitch), WASD + Q/E moves, R resets.
// Also where the window has moved the scene's lights (J/L, U/O, I/K along
// world x, y, z), which the frame setup's pose carries to the workers.
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
  // Back home (where the last follow() put it, or the camera it started at).
  void reset();
  // An animated camera: home and camera become `c`, unless the user has
  // placed the camera since the start or the last reset(). Not a change
  // (no new generation): the frames that follow the animation carry it.
  void follow(const Camera& c);
  // Whether the user placed the camera (look(), move(), hold()) since the
  // start or the last reset(): then it no longer follows an animation.
  bool placed() const { return placed_; }
  // Placed where it is (a camera loaded from a bookmark).
  void hold() { placed_ = true; }
  // Axes in [-1, 1] along world x, y, z, held for `seconds`.
  void move_lights(float x, float y, float z, float seconds);
  glm::vec3 light_offset() const { return light_offset_; }
  const Camera& camera() const { return camera_; }
  // Bumped by every change: frames rendered with an older generation are stale.
  uint64_t generation() const { return generation_; }

 private:
  void update();
  Camera home_, camera_;
  float yaw_ = 0.0f, pitch_ = 0.0f, speed_;
  glm::vec3 home_forward_, right_;
  glm::vec3 light_offset_{0.0f};
  uint64_t generation_ = 0;
  bool placed_ = false;
};

}  // namespace igi
