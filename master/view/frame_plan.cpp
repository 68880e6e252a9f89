#include "view/frame_plan.h"

#include <algorithm>
#include <cmath>

#include "core/passes.h"
#include "scene/animation.h"

namespace igi {

double camera_path_angle(const CameraPath& path, int i) {
  constexpr double kTurn = 2.0 * 3.14159265358979323846;
  const double frames = std::max(path.frames, 1);
  switch (path.kind) {
    case CameraPath::Kind::None: return 0.0;
    case CameraPath::Kind::Orbit:
      return path.orbit_step_degrees != 0.0 ? path.orbit_step_degrees * (kTurn / 360.0) * i : kTurn * i / frames;
    case CameraPath::Kind::Swing: return path.swing_degrees * (kTurn / 360.0) * std::sin(kTurn * i / frames);
  }
  return 0.0;
}

FrameSetup plan_frame(const RenderOptions& render, const CameraPath& camera_path, const Scene& scene, int i,
                      bool progressive) {
  FrameSetup f;
  f.frame_id = uint64_t(i);
  f.width = render.width;
  f.height = render.height;
  f.seed = render.seed;
  const bool pt = render.settings.method == MethodKind::PathTracer;
  const bool animated = scene.animation && scene.animation->animated();
  progressive = progressive && !animated;  // each frame of an animation stands at a time of its own
  f.sample_count = pt ? uint32_t(render.samples) : 1;
  if (progressive) f = progressive_pass(f, render.settings.method, uint32_t(i), f.sample_count);  // core/passes.h
  f.pose.light_offset = render.light_offset;
  if (animated)
    f.pose.time = scene_time(render.time, render.time_step, uint64_t(i), render.loop, scene.animation->duration);
  f.camera = scene_camera(scene, f.pose.time);  // where an animated camera stands then
  const double angle = camera_path_angle(camera_path, i);
  if (angle != 0.0) {
    const Camera& c = f.camera;
    const glm::vec3 forward = glm::normalize(c.forward);
    const float along = glm::dot(scene.bounds().center() - c.position, forward);
    const glm::vec3 pivot = c.position + std::max(along, 0.0f) * forward;
    const float a = float(angle);
    const glm::mat3 r(glm::vec3(std::cos(a), 0, -std::sin(a)), glm::vec3(0, 1, 0), glm::vec3(std::sin(a), 0, std::cos(a)));
    f.camera.position = pivot + r * (c.position - pivot);
    f.camera.forward = r * c.forward;
    f.camera.up = r * c.up;
  }
  return f;
}

}  // namespace igi
