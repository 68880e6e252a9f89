#pragma once
// A scene with its BVH and lights, posed frame by frame: what a worker (or
// any process that renders) holds for a session.
//
// The area lights are grouped into a part of their own at construction
// (scene/animation.h), so the window can move them; a scene with area lights
// therefore traces two-level (accel.h). set_pose() moves what moves, rebuilds
// just the moving parts' BVHs and re-weighs the lights: its cost grows with
// what moves, never with the static geometry.
#include <memory>
#include <optional>

#include "core/method.h"
#include "lighting/lights.h"
#include "scene/accel.h"
#include "scene/animation.h"

namespace igi {

class SceneState {
 public:
  explicit SceneState(Scene scene);
  SceneState(const SceneState&) = delete;
  SceneState& operator=(const SceneState&) = delete;

  // Puts the scene at `pose`; nothing to do when it stands there already.
  // Not while anything traces or samples the scene. Returns whether it moved.
  bool set_pose(const ScenePose& pose);
  // The pose set last; none before the first set_pose (the scene stands as loaded).
  const std::optional<ScenePose>& pose() const { return pose_; }
  // Whether any pose differs from the loaded scene: an animation, or area or punctual lights to move.
  bool posable() const { return scene_.animation != nullptr; }

  const Scene& scene() const { return scene_; }
  const Accel& accel() const { return *accel_; }
  const LightSet& lights() const { return *lights_; }
  SceneContext context() const { return {scene_, *accel_, *lights_}; }

 private:
  Bounds posed_bounds() const;

  Scene scene_;
  std::unique_ptr<Accel> accel_;
  std::unique_ptr<LightSet> lights_;
  Bounds static_bounds_;  // of the triangles that never move
  std::optional<ScenePose> pose_;
};

}  // namespace igi
