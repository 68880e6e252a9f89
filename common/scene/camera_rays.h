#pragma once
// Primary rays of a pinhole camera. Pixel (0,0) is the top-left pixel; a film
// point (x, y) in pixel units runs right and down.
#include <cmath>

#include <glm/glm.hpp>

#include "scene/accel.h"
#include "scene/scene.h"

namespace igi {

struct CameraBasis {
  glm::vec3 origin, forward, right, down;  // right/down scaled to one pixel
  float pixel_x0, pixel_y0;                // film offset of the image centre

  CameraBasis(const Camera& cam, int width, int height) {
    origin = cam.position;
    forward = glm::normalize(cam.forward);
    glm::vec3 r = glm::normalize(glm::cross(forward, cam.up));
    glm::vec3 u = glm::cross(r, forward);
    float pixel = 2.0f * std::tan(0.5f * cam.vfov) / float(height);
    right = r * pixel;
    down = -u * pixel;
    pixel_x0 = 0.5f * float(width);
    pixel_y0 = 0.5f * float(height);
  }
  // Unnormalised direction through film point (x, y).
  glm::vec3 direction(float x, float y) const {
    return forward + (x - pixel_x0) * right + (y - pixel_y0) * down;
  }
  Ray ray(float x, float y) const { return Ray{origin, glm::normalize(direction(x, y))}; }
};

}  // namespace igi
