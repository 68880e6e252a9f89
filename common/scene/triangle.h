#pragma once
// A triangle's plane from its corners: counter-clockwise winding is the front.
#include <cstdint>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace igi {

// cross(p1 - p0, p2 - p0): the front normal, scaled by twice the area.
inline glm::vec3 triangle_cross(glm::vec3 p0, glm::vec3 p1, glm::vec3 p2) { return glm::cross(p1 - p0, p2 - p0); }
// The unit front normal (NaN for a triangle of no area).
inline glm::vec3 triangle_normal(glm::vec3 p0, glm::vec3 p1, glm::vec3 p2) {
  return glm::normalize(triangle_cross(p0, p1, p2));
}

// The same for Scene::triangles[index].
inline glm::vec3 triangle_cross(const Scene& scene, uint32_t index) {
  const glm::uvec3& t = scene.triangles[index];
  return triangle_cross(scene.positions[t[0]], scene.positions[t[1]], scene.positions[t[2]]);
}
inline glm::vec3 triangle_normal(const Scene& scene, uint32_t index) {
  return glm::normalize(triangle_cross(scene, index));
}

}  // namespace igi
