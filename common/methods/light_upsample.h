#pragma once
// Light shaded on a coarse lattice, shown on every pixel (--light-divisor D,
// the window's previews while the camera moves: master/view/frame_budget.h).
//
// Every pixel's camera ray is traced at full resolution: what it shows (the
// surface, its normal and depth, its albedo and textures, mirrors and glass
// on the way, emission) stays sharp. Light, the costly part (VPL shadow rays,
// glossy gathers, compensation, exact lights), is shaded and filtered on the
// lattice of one pixel in D x D (core/gbuffer.h: lattice pixel (x, y) stands
// for image pixel (x D + D/2, y D + D/2)), as if the lattice were the image.
// Each pixel then takes the demodulated light of the lattice samples around
// it and multiplies it by its own albedo: joint bilateral upsampling (Kopf et
// al. 2007) with the discontinuity buffer's idea of a surface. Of the 2 x 2
// lattice samples around the pixel, those on its surface (normals within
// kNormalCos, the pixel's point within kPlaneTolerance x its depth of the
// sample's tangent plane) are weighed bilinearly; where none is, the 4 x 4
// around it, by distance; where none is either (a chain or a leaf thinner
// than D pixels), the light of the nearest sample with a surface. So light
// never crosses an edge where the surface across it has its own samples, and
// a flat wall's light is the lattice's, interpolated.
//
// Pure: a pixel's light is a function of its own sample and the lattice
// samples (and their light) around it, whatever tile computes it; the
// lattice's light depends only on lattice coordinates (the methods treat the
// lattice as the image), so whole = tiled = distributed holds bit for bit.
#include <span>

#include <glm/glm.hpp>

#include "core/frame.h"
#include "core/gbuffer.h"

namespace igi {

// The lattice cells that the pixels of `job` read (the 4 x 4 around each),
// in lattice coordinates, clipped to the lattice of `step` over a
// width x height image; with `border` lattice pixels of border.
TileJob lattice_cells(const TileJob& job, int step, int width, int height, int border);

struct LatticeLight {
  const GBuffer& lattice;            // the lattice's samples: a region with a step
  std::span<const glm::vec3> light;  // demodulated light per lattice sample, laid out as lattice.layers
                                     // (read only where the sample is valid and within the cells)
  TileJob cells;                     // where `light` is known (lattice_cells, border aside)
};

// The demodulated light at `g`, layer `layer` of image pixel (x, y).
glm::vec3 upsample_light(const LatticeLight& lattice, int layer, const GSample& g, int x, int y);

namespace upsample {
inline constexpr float kNormalCos = 0.9f;
inline constexpr float kPlaneTolerance = 0.02f;  // of the pixel's depth
}  // namespace upsample

}  // namespace igi
