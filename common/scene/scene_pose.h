#pragma once
// Where a scene stands in one frame: plain data the frame setup carries, so
// every worker poses the scene identically (scene/animation.h does it).
#include <glm/glm.hpp>

namespace igi {

struct ScenePose {
  double time = 0.0;             // seconds of animation time (glTF key times)
  glm::vec3 light_offset{0.0f};  // metres the window moved the lights by
  bool operator==(const ScenePose&) const = default;
};

}  // namespace igi
