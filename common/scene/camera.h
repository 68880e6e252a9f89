#pragma once
// The camera on its own: frames and messages carry it without the scene model.
#include <glm/glm.hpp>

namespace igi {

// Pinhole camera. The image plane's vertical field of view is vfov radians;
// the horizontal extent follows from the image's aspect ratio.
struct Camera {
  glm::vec3 position{0.0f};
  glm::vec3 forward{0.0f, 0.0f, -1.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float vfov = 0.6859f;  // 39.3 degrees
};

}  // namespace igi
