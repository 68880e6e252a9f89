#include "display/camera_controller.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace igi {

CameraController::CameraController(const Camera& home, float speed) : home_(home), camera_(home), speed_(speed) {
  home_forward_ = glm::normalize(home.forward);
  right_ = glm::normalize(glm::cross(home_forward_, home.up));
}

void CameraController::follow(const Camera& c) {
  if (placed_) return;
  home_ = camera_ = c;
  yaw_ = pitch_ = 0.0f;
  home_forward_ = glm::normalize(c.forward);
  right_ = glm::normalize(glm::cross(home_forward_, c.up));
}

void CameraController::look(float dx, float dy) {
  if (dx == 0.0f && dy == 0.0f) return;
  yaw_ -= 0.004f * dx;
  pitch_ = std::clamp(pitch_ - 0.004f * dy, -1.5f, 1.5f);
  update();
}

void CameraController::move(float forward, float right, float up, float seconds) {
  if (forward == 0.0f && right == 0.0f && up == 0.0f) return;
  const glm::vec3 f = glm::normalize(camera_.forward);
  const glm::vec3 r = glm::normalize(glm::cross(f, camera_.up));
  camera_.position += speed_ * seconds * (forward * f + right * r + up * glm::normalize(camera_.up));
  placed_ = true;
  ++generation_;
}

void CameraController::move_lights(float x, float y, float z, float seconds) {
  if (x == 0.0f && y == 0.0f && z == 0.0f) return;
  light_offset_ += 0.5f * speed_ * seconds * glm::vec3(x, y, z);
  ++generation_;
}

void CameraController::reset() {
  camera_ = home_;
  yaw_ = pitch_ = 0.0f;
  placed_ = false;
  ++generation_;
}

// Forward = home forward turned by yaw about up, then by pitch about right.
void CameraController::update() {
  const glm::vec3 up = glm::normalize(home_.up);
  glm::mat4 turn = glm::rotate(glm::mat4(1.0f), yaw_, up);
  glm::vec3 right = glm::vec3(turn * glm::vec4(right_, 0.0f));
  turn = glm::rotate(glm::mat4(1.0f), pitch_, right) * turn;
  camera_.forward = glm::normalize(glm::vec3(turn * glm::vec4(home_forward_, 0.0f)));
  placed_ = true;
  ++generation_;
}

}  // namespace igi
