#pragma once
// Where a pixel's random numbers come from: every one is addressed by
// (pixel, sequence, sample index, dimension) under a frame seed, as pbrt's
// samplers address theirs by (pixel, sample index, dimension), and is a pure
// function of that address (Owen-scrambled Sobol, sampling/sobol.h): a tile,
// a thread or another process that asks for the same address gets the same
// number, in any order. The methods use these seeds and no other recipe:
//
//   pixel(x, y)            the pixel's own sequence: pt's paths (sample index =
//                          the pixel's sample, dimensions along the path)
//   sequence(x, y, s)      a sequence of the pixel's own, s: a sub-sample's
//                          specular choices (core/camera_front_end.h), a glass
//                          branch's compensation rays (methods/bias_compensation.cpp)
//   sequence(x, y, s, t)   the same under a tag t that keeps it apart from the
//                          others (the glossy gather of layer s)
//   drawn(x, y, s)         --vpl-draws' points (methods/vpl_method.cpp): the
//                          frame seed hashed first, then the pixel, an older
//                          order kept so their pixels stay as they were
//
// ConsistentValues (tests/common/sampling/test_pixel_samples.cpp) revisits addresses in
// another order and gets the same values.
#include <cstdint>

#include <glm/vec2.hpp>

#include "sampling/hash.h"
#include "sampling/sobol.h"

namespace igi {

struct PixelSamples {
  uint32_t frame_seed;  // FrameSetup::seed, or a method's seed derived from it

  constexpr uint32_t pixel(int x, int y) const { return hash(uint32_t(x), uint32_t(y), frame_seed); }
  constexpr uint32_t sequence(int x, int y, uint32_t s) const { return hash(pixel(x, y), s); }
  constexpr uint32_t sequence(int x, int y, uint32_t s, uint32_t tag) const { return hash(pixel(x, y), s, tag); }
  constexpr uint32_t drawn(int x, int y, uint32_t s) const {
    return hash(hash(frame_seed, uint32_t(x), uint32_t(y)), s);
  }
  // Dimensions d and d + 1 (d even) of sample `index` of the pixel's own sequence.
  glm::vec2 sample_2d(int x, int y, uint32_t index, uint32_t dimension) const {
    return igi::sample_2d(index, dimension, pixel(x, y));
  }
};

}  // namespace igi
