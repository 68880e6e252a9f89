#pragma once
// The one camera front end: where every method's camera paths start. The
// G-buffer (core/gbuffer.cpp), pt (methods/path_tracer.cpp), lightcuts'
// gather points and the camera points of light importance and bidirectional
// IR (importance/camera_points.cpp) all take their camera rays here:
//   - the frame's pinhole camera (scene/camera_rays.h: pixel (0, 0) top-left),
//   - a film point in pixel units, or sub-sample k of a pixel at the
//     frame's jitter (core/subpixel.h),
//   - kCameraRayMask, which culls the backs of single-sided faces and which
//     the specular chain keeps (core/gbuffer.h: follow_specular_chain and
//     follow_specular_tree, the chain through mirrors and glass),
//   - the seed of a sub-sample's specular choices, from its global pixel.
// A camera ray is therefore a pure function of the frame and the film point:
// the same in every tile, thread and worker.
#include <cstdint>

#include "core/frame.h"
#include "core/subpixel.h"
#include "sampling/hash.h"
#include "scene/accel.h"
#include "scene/camera_rays.h"
#include "sampling/pixel_samples.h"

namespace igi {

class CameraFrontEnd {
 public:
  // `samples_per_pixel`: the sub-samples of a pixel, a square (1, 4, 9 ...).
  CameraFrontEnd(const FrameSetup& frame, int samples_per_pixel = 1)
      : basis_(frame.camera, frame.width, frame.height), frame_(frame),
        side_(std::max(1, subpixel_side(samples_per_pixel))) {}

  // The camera ray through film point (x, y), in pixel units.
  Ray ray(float x, float y) const {
    return Ray{basis_.origin, glm::normalize(basis_.direction(x, y)), 0.0f, 1e30f, kCameraRayMask};
  }
  // Film offset of sub-sample k inside every pixel, and its ray through pixel (x, y), image coordinates.
  glm::vec2 subpixel(int k) const { return subpixel_offset(k, side_, frame_.jitter_x, frame_.jitter_y); }
  Ray pixel_ray(int x, int y, int k) const {
    const glm::vec2 offset = subpixel(k);
    return ray(float(x) + offset.x, float(y) + offset.y);
  }
  // The seed of the specular choices (glass: reflect or refract) of sub-sample k of pixel (x, y).
  uint32_t chain_seed(int x, int y, int k) const {
    return PixelSamples{frame_.seed}.sequence(x, y, uint32_t(k));
  }
  const FrameSetup& frame() const { return frame_; }

 private:
  CameraBasis basis_;
  FrameSetup frame_;
  int side_;
};

}  // namespace igi
