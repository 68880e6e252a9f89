#pragma once
// One frame as plain data: what the master sends once per frame, and the
// tile jobs it streams. No pointers, so both travel over the wire unchanged.
#include <cstdint>

#include "scene/camera.h"
#include "scene/scene_pose.h"

namespace igi {

struct FrameSetup {
  uint64_t frame_id = 0;
  Camera camera;
  int width = 0;
  int height = 0;
  uint32_t seed = 0;          // scrambles every sample of the frame
  // pt: first sample index of this pass. ir/igi/lightcuts: the progressive
  // pass this frame is (0 for a frame on its own): the clamp relaxes with it
  // (core/clamp.h).
  uint32_t sample_begin = 0;
  uint32_t sample_count = 1;  // pt: samples per pixel in this pass
  // ir/igi: where in each pixel the primary ray goes ((0.5, 0.5) = centre);
  // progressive passes move it to antialias.
  float jitter_x = 0.5f, jitter_y = 0.5f;
  ScenePose pose;  // the scene's animation time and moved lights in this frame
  // Each TileResult also carries its pixels' surfaces (PixelSurface): the
  // master's reprojection asks for them (render/view_history.h).
  bool want_surfaces = false;
};

// The first surface one camera ray through a pixel meets (its sub-sample 0 at
// the frame's jitter: core/pixel_surface.h): what the master needs to carry
// the pixel's history into a new view. Plain bytes on the wire, 8 a pixel.
struct PixelSurface {
  static constexpr uint8_t kViewDependent = 1;  // glossy, mirror or glass: its colour changes with the view
  float depth = 0.0f;            // distance along the ray; 0: the ray leaves the scene
  int8_t normal[3] = {0, 0, 0};  // shading normal facing the ray, snorm8 (x 127)
  uint8_t flags = 0;             // kViewDependent or 0
  bool operator==(const PixelSurface&) const = default;
};

// A rectangle of the image, rendered with `border` extra pixels on each side
// (clipped to the image) that the filter reads but the result leaves out.
struct TileJob {
  int x = 0, y = 0, w = 0, h = 0;
  int border = 0;
};

struct RayCounts {
  uint64_t primary = 0, shadow = 0, secondary = 0;
  uint64_t total() const { return primary + shadow + secondary; }
  RayCounts& operator+=(const RayCounts& o) {
    primary += o.primary; shadow += o.shadow; secondary += o.secondary;
    return *this;
  }
};

}  // namespace igi
