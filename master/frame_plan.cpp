#include "frame_plan.h"

#include <cmath>

#include "sampling/sobol.h"
#include "scene/animation.h"

namespace igi {

FrameSetup plan_frame(const RenderOptions& render, const std::string& camera_path, const Scene& scene, int i,
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
  if (progressive) {
    if (pt) {  // the pass continues the sample sequence: same seed, the next samples
      f.sample_begin = uint32_t(i * render.samples);
    } else {   // a new estimate: new VPLs, and the next point of one 2D sample set for the sub-pixel position
      f.seed += uint32_t(i);
      f.sample_begin = uint32_t(i);  // the pass: the clamp relaxes with it
      const glm::vec2 j = sample_2d(uint32_t(i), 0, render.seed);
      f.jitter_x = j.x;
      f.jitter_y = j.y;
    }
  }
  f.pose.light_offset = render.light_offset;
  if (animated)
    f.pose.time = scene_time(render.time, render.time_step, uint64_t(i), render.loop, scene.animation->duration);
  f.camera = scene_camera(scene, f.pose.time);  // where an animated camera stands then
  if (camera_path == "orbit") {  // turn about the vertical axis through the scene's centre
    const glm::vec3 c = scene.bounds().center();
    const float angle = 0.02f * float(i);
    const glm::mat3 r(glm::vec3(std::cos(angle), 0, -std::sin(angle)), glm::vec3(0, 1, 0),
                      glm::vec3(std::sin(angle), 0, std::cos(angle)));
    f.camera.position = c + r * (f.camera.position - c);
    f.camera.forward = r * f.camera.forward;
  }
  return f;
}

}  // namespace igi
