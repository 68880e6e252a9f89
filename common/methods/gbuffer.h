#pragma once
// First non-specular surface seen through each pixel of a tile region: the
// input to VPL shading and to the discontinuity buffer.
#include <vector>

#include <glm/glm.hpp>

#include "methods/ray_log.h"
#include "render/frame.h"
#include "scene/accel.h"
#include "scene/surface.h"

namespace igi {

struct GSample {
  SurfacePoint surface;           // valid only when depth is finite
  glm::vec3 wo{0.0f};             // towards the viewer (the last specular vertex)
  glm::vec3 throughput{1.0f};     // product of specular weights along the chain
  glm::vec3 emitted{0.0f};        // emission seen along the chain, weighted
  float depth = INFINITY;         // path length from the camera; infinite: nothing diffuse seen
  bool valid() const { return depth < INFINITY; }
};

struct Region {
  int x0 = 0, y0 = 0, width = 0, height = 0;  // image coordinates
};

// The tile plus its border, clipped to the image.
Region tile_region(const TileJob& job, int image_width, int image_height);

// Primary rays in 16-wide packets (4x4 pixels), then specular chains (mirror,
// glass) followed one ray at a time up to max_depth. Glass picks reflection or
// refraction with a number hashed from the pixel and seed.
void build_gbuffer(const Accel& accel, const FrameSetup& frame, const Region& region, int max_depth,
                   std::vector<GSample>& out, RayCounts& rays, RayLog* log = nullptr);

}  // namespace igi
