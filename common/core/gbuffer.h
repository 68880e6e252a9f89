#pragma once
// First non-specular surface seen through each sub-sample of each pixel of a
// tile region: the input to VPL shading and to the discontinuity buffer.
#include <algorithm>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "core/frame.h"
#include "core/ray_log.h"
#include "core/settings.h"
#include "scene/accel.h"
#include "scene/surface.h"

namespace igi {

struct GSample {
  SurfacePoint surface;           // meaningful only when valid()
  glm::vec3 wo{0.0f};             // towards the viewer (the last specular vertex)
  glm::vec3 throughput{1.0f};     // product of specular weights along the chain
  glm::vec3 emitted{0.0f};        // emission seen along the chain, weighted
  float depth = INFINITY;         // path length from the camera (the filter's depth); infinite where not valid()
  bool has_surface = false;       // a non-specular surface was found: surface and wo hold it
  bool valid() const { return has_surface; }
};

// A lattice over the image, one pixel in `step` x `step`: lattice pixel
// (x, y) stands for image pixel (x step + step / 2, y step + step / 2),
// clipped to the image (step 1: the image itself). Light shaded on it is
// upsampled to every pixel (methods/light_upsample.h).
inline int lattice_extent(int image_extent, int step) { return (image_extent + step - 1) / step; }
inline int lattice_to_image(int c, int step, int image_extent) { return std::min(c * step + step / 2, image_extent - 1); }

struct Region {
  int x0 = 0, y0 = 0, width = 0, height = 0;  // image coordinates (with a step, lattice coordinates)
  int step = 1;                               // > 1: the region is a piece of that lattice
  size_t pixels() const { return size_t(width) * size_t(height); }
  size_t index(int x, int y) const { return size_t(y - y0) * size_t(width) + size_t(x - x0); }  // image coordinates
};

// The tile plus its border, clipped to the image.
Region tile_region(const TileJob& job, int image_width, int image_height);

// The region's layers: S sub-sample positions (core/subpixel.h) times the
// glass branches. Layer l = b S + k holds branch b of sub-sample k of every
// pixel, row-major, so each layer reads like a one-sample G-buffer of the
// region and the discontinuity buffer filters it on its own. Branch 0 is
// where the camera ray's chain ends (refracted at glass, or reflected under
// total internal reflection); branch b > 0 is the b-th reflection split off a
// glass surface along the way (see follow_specular_tree), invalid where
// there was none. Only the branches some pixel of the region reached are
// present (`branches` <= the setting): a tile without glass has S layers and
// costs what it did before glass branches existed.
struct GBuffer {
  Region region;
  int samples = 1;   // S
  int branches = 1;  // branches present in this region, 1 <= branches <= --glass-branches
  std::vector<GSample> layers;  // at least S branches region.pixels(); the rest is scratch

  int layer_count() const { return samples * branches; }
  // Shading points in the present layers (layers.size() may hold more: scratch).
  size_t points() const { return size_t(layer_count()) * region.pixels(); }
  // The sub-sample a layer belongs to (its VPL group, its position).
  int subsample_of_layer(int layer) const { return layer % samples; }
  GSample& at(int layer, size_t pixel) { return layers[size_t(layer) * region.pixels() + pixel]; }
  const GSample& at(int layer, size_t pixel) const { return layers[size_t(layer) * region.pixels() + pixel]; }
};

// Primary rays in 16-wide packets (4x4 pixels of one sub-sample position),
// then mirrors and glass followed one ray at a time, each sub-sample into
// `glass_branches` layers (follow_specular_tree). Camera rays skip the back
// of single-sided faces (scene/accel.h). A region with a step traces its
// lattice's pixels, 4 x 4 of the lattice to a packet: a lattice pixel's
// sample is its image pixel's ray (the packet's other rays differ).
// `surfaces` (a region without a step: one a region pixel, or empty): what
// each pixel's sub-sample 0 hits first (core/pixel_surface.h), the ray
// trace_pixel_surfaces() would trace, so it is not traced twice.
void build_gbuffer(const Accel& accel, const FrameSetup& frame, const Region& region, int samples,
                   int glass_branches, int specular_depth, GBuffer& out, RayCounts& rays, RayLog* log = nullptr,
                   std::span<PixelSurface> surfaces = {});

// Follows mirrors and glass from `hit` (found along `ray`) to the first
// non-specular surface, at most `specular_depth` surfaces in all, filling
// `g` (left invalid when the chain ends elsewhere). Glass picks reflection or
// refraction by Fresnel with numbers hashed from `seed` and the depth. Camera
// rays pass kCameraRayMask, which the chain keeps.
void follow_specular_chain(const Accel& accel, Ray ray, Hit hit, uint32_t seed, int specular_depth, GSample& g,
                           RayCounts& rays);

// As follow_specular_chain, but the first B - 1 glass surfaces where both
// reflection and refraction are possible split the path instead of picking:
// the refracted part continues in the same branch with weight (1 - F) tint,
// the reflected part becomes branch `used` (the next free one) with weight
// F, followed after the current branch ends (depth first). Past the budget,
// glass picks by Fresnel as follow_specular_chain does (branch 0 with the
// same numbers). Every branch is an unbiased estimate of its part, and their
// sum is the pixel's: the split changes the noise, never the mean.
// `out[b]` receives branch b, reset first, for the b < returned count that
// were created; the others are not touched.
int follow_specular_tree(const Accel& accel, Ray ray, Hit hit, uint32_t seed, int specular_depth, int branches,
                         GSample* const* out, RayCounts& rays);

}  // namespace igi
