#pragma once
// The Cornell box with its vertex normals tilted 12 degrees off the faces, in
// a different direction at every vertex: a smooth-shaded mesh whose shading
// normals disagree with the geometry, for the shading rule and the bounds.
#include <cmath>

#include "sampling/warp.h"
#include "scene/builtin_scenes.h"
#include "scene/triangle.h"

namespace igi::test {

inline Scene tilted_cornell() {
  Scene s = make_cornell_box();
  s.normals.assign(s.positions.size(), glm::vec3(0.0f));
  for (size_t t = 0; t < s.triangles.size(); ++t) {
    const glm::uvec3 tri = s.triangles[t];
    const glm::vec3 n = triangle_normal(s, uint32_t(t));
    const Onb f(n);
    for (int k = 0; k < 3; ++k) {
      const float phi = 2.1f * float(tri[k]);
      s.normals[tri[k]] = glm::normalize(n + std::tan(0.21f) * (std::cos(phi) * f.t + std::sin(phi) * f.b));
    }
  }
  s.name = "tilted-cornell";
  return s;
}

}  // namespace igi::test
