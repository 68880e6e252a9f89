#include "render/scene_state.h"

#include <utility>
#include <vector>

namespace igi {

SceneState::SceneState(Scene scene) : scene_(std::move(scene)) {
  group_area_lights(scene_);
  std::vector<bool> moving(scene_.triangles.size(), false);
  if (scene_.animation)
    for (const DynamicPart& part : scene_.animation->parts)
      for (uint32_t t : part.triangles) moving[t] = true;
  for (size_t t = 0; t < scene_.triangles.size(); ++t)
    if (!moving[t])
      for (int k = 0; k < 3; ++k) static_bounds_.extend(scene_.positions[scene_.triangles[t][k]]);
  accel_ = std::make_unique<Accel>(scene_);
  lights_ = std::make_unique<LightSet>(scene_);
}

bool SceneState::set_pose(const ScenePose& pose) {
  if (pose_ && *pose_ == pose) return false;
  const bool moved = posable() && (pose_ || pose != ScenePose{} || scene_.animation->animated());
  pose_ = pose;
  if (!moved) return false;
  pose_scene(scene_, pose);
  accel_->update();
  lights_->refresh(posed_bounds());
  return true;
}

Bounds SceneState::posed_bounds() const {
  Bounds b = static_bounds_;
  for (const DynamicPart& part : scene_.animation->parts)
    for (uint32_t t : part.triangles)
      for (int k = 0; k < 3; ++k) b.extend(scene_.positions[scene_.triangles[t][k]]);
  return b;
}

}  // namespace igi
