#pragma once
// First non-specular surface seen through each sub-sample of each pixel of a
// tile region: the input to VPL shading and to the discontinuity buffer.
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
  size_t pixels() const { return size_t(width) * size_t(height); }
  size_t index(int x, int y) const { return size_t(y - y0) * size_t(width) + size_t(x - x0); }  // image coordinates
};

// The tile plus its border, clipped to the image.
Region tile_region(const TileJob& job, int image_width, int image_height);

// S layers of the region, one per sub-sample position (methods/subpixel.h):
// layer k holds sub-sample k of every pixel, row-major, so each layer reads
// like a one-sample G-buffer of the region.
struct GBuffer {
  Region region;
  int samples = 1;
  std::vector<GSample> layers;  // samples * region.pixels()

  GSample& at(int k, size_t pixel) { return layers[size_t(k) * region.pixels() + pixel]; }
  const GSample& at(int k, size_t pixel) const { return layers[size_t(k) * region.pixels() + pixel]; }
};

// Primary rays in 16-wide packets (4x4 pixels of one layer), then specular
// chains (mirror, glass) followed one ray at a time. Camera rays skip the
// back of single-sided faces (scene/accel.h).
void build_gbuffer(const Accel& accel, const FrameSetup& frame, const Region& region, int samples,
                   int specular_depth, GBuffer& out, RayCounts& rays, RayLog* log = nullptr);

// Follows mirrors and glass from `hit` (found along `ray`) to the first
// non-specular surface, at most `specular_depth` surfaces in all, filling
// `g` (left invalid when the chain ends elsewhere). Glass picks reflection or
// refraction by Fresnel with numbers hashed from `seed` and the depth. Camera
// rays pass kCameraRayMask, which the chain keeps.
void follow_specular_chain(const Accel& accel, Ray ray, Hit hit, uint32_t seed, int specular_depth, GSample& g,
                           RayCounts& rays);

}  // namespace igi
