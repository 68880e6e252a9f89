#pragma once
// Gather points: where a pixel's camera rays (after mirrors and glass) first
// meet a surface that light is gathered at. Plain lightcuts take one per
// pixel at the frame's jitter, like ir; multidimensional lightcuts take
// K = s x s per pixel, sub-sample k in cell (k mod s, k div s) of the pixel's
// grid at the frame's jitter inside the cell. Everything is a function of
// the GLOBAL pixel coordinates, the sub-sample and the frame: a pixel's gather
// points do not depend on its tile.
//
// Sub-sample positions and the specular chain are the VPL methods'
// (core/subpixel.h, core/gbuffer.h), camera rays culling single-sided
// back faces like theirs.
#include <cstdint>

#include <glm/glm.hpp>

#include "core/camera_front_end.h"
#include "core/frame.h"
#include "core/gbuffer.h"
#include "lightcuts/bounds.h"
#include "sampling/warp.h"
#include "scene/accel.h"
#include "scene/surface.h"

namespace igi::lightcuts {

struct GatherPoint {
  SurfacePoint surface;         // valid only when depth is finite
  glm::vec3 wo{0.0f};           // towards the viewer (the last specular vertex)
  glm::vec3 throughput{1.0f};   // product of specular weights along the chain
  glm::vec3 emitted{0.0f};      // emission seen along the chain, weighted
  float depth = INFINITY;       // path length from the camera
  // Facing the viewer's side of the surface, for the bounds.
  glm::vec3 shading_normal{0.0f}, geometric_normal{0.0f};
  float cos_o = 0.0f;           // dot(wo, shading_normal)
  // Frames around the shading normal, the geometric normal and -wo: the bounds (lightcuts/cluster_bound.h) ask
  // for cosines against these at every cluster.
  BoundFrame shading_frame{glm::vec3(0.0f, 0.0f, 1.0f)}, geometric_frame{glm::vec3(0.0f, 0.0f, 1.0f)};
  BoundFrame back_frame{glm::vec3(0.0f, 0.0f, 1.0f)};
  float tilt_sin = 0.0f;        // sin of the angle between shading and geometric normal
  bool valid() const { return depth < INFINITY; }
};

// The gather point at the end of a specular chain (core/gbuffer.h):
// its surface, direction, emission and throughput, and the frames.
GatherPoint gather_point(const GSample& chain);

class GatherPointTracer {
 public:
  GatherPointTracer(const Accel& accel, const FrameSetup& frame, int samples_per_pixel, int specular_depth);
  // Sub-sample k (< samples_per_pixel) of pixel (x, y), image coordinates.
  GatherPoint trace(int x, int y, int k, RayCounts& rays) const;

 private:
  const Accel& accel_;
  CameraFrontEnd camera_;
  int specular_depth_;
};

}  // namespace igi::lightcuts
