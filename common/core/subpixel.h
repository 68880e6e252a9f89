#pragma once
// Anti-aliasing by VPL groups (after Benthin, Wald and Slusallek 2003).
//
// A pixel takes S = s x s primary rays at stratified sub-pixel positions.
// Its VPL set is split into S groups of light paths (core/vpl.h), and
// sub-sample k connects only to group g = (k + r_p) mod S, scaled by S, so
// the pixel's mean over its sub-samples is still an unbiased estimate of the
// whole set, while it casts the same number of shadow rays as with S = 1:
//   L_p = 1/S sum_k S L_{group g(k)}(x_k) = sum_g L_g(x_{k(g)}).
// r_p, a hash of the GLOBAL pixel coordinates, rotates which corner of the
// pixel each group lights, so no group is tied to one sub-pixel position
// (an edge would otherwise always see the same group's error).
//
// Sub-sample k sits in cell (k mod s, k div s) of the pixel's s x s grid,
// at the frame's jitter inside the cell: (0.5, 0.5) puts it at the cell's
// centre; progressive passes move it. S = 1 is the pixel at the jitter.
#include <cmath>

#include <glm/vec2.hpp>

#include "sampling/hash.h"
#include "sampling/pixel_samples.h"

namespace igi {

// The side s of an S-sample grid, or 0 when S is not a square number >= 1.
inline int subpixel_side(int samples) {
  if (samples < 1) return 0;
  const long s = std::lround(std::sqrt(double(samples)));
  return s * s == long(samples) ? int(s) : 0;  // 64-bit: 46341^2 overflows an int
}

// Film offset of sub-sample k inside its pixel, in [0, 1)^2.
inline glm::vec2 subpixel_offset(int k, int side, float jitter_x, float jitter_y) {
  return {(float(k % side) + jitter_x) / float(side), (float(k / side) + jitter_y) / float(side)};
}

inline int subpixel_rotation(int x, int y, int samples) {
  return samples > 1 ? int(PixelSamples{0x61617367u /* "aasg" */}.pixel(x, y) % uint32_t(samples)) : 0;
}

// The VPL group that sub-sample k of pixel (x, y) connects to, and back.
inline int group_of_subsample(int x, int y, int k, int samples) {
  return (k + subpixel_rotation(x, y, samples)) % samples;
}
inline int subsample_of_group(int x, int y, int group, int samples) {
  const int k = group - subpixel_rotation(x, y, samples);  // in (-samples, samples): no second division
  return k < 0 ? k + samples : k;
}

}  // namespace igi
