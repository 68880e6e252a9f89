#pragma once
// Addressable low-discrepancy sampler: padded, shuffled, Owen-scrambled Sobol
// (Burley 2020, "Practical Hash-based Owen Scrambling").
//
// sample(index, dimension, seed) is a pure function: the same arguments give
// the same value in any order, on any thread, in any process. Dimensions come
// in pairs; each pair is the 2D Sobol (0,2)-sequence with its own index shuffle
// and its own nested-uniform scramble, so every 2D projection (2d, 2d+1) keeps
// the (0,m,2)-net property for power-of-two prefixes: the first 2^m samples
// put exactly one point into every elementary interval of area 2^-m.
#include <cstdint>

#include <glm/vec2.hpp>

namespace igi {

uint32_t sobol_dim0(uint32_t index);  // van der Corput radical inverse, 0.32 fixed point
uint32_t sobol_dim1(uint32_t index);  // Sobol's second dimension, 0.32 fixed point
// Nested-uniform (Owen) scramble of a 0.32 fixed-point value.
uint32_t owen_scramble(uint32_t value, uint32_t seed);

float sample_1d(uint32_t index, uint32_t dimension, uint32_t seed);
// Dimensions `dimension` and `dimension + 1`; dimension must be even.
glm::vec2 sample_2d(uint32_t index, uint32_t dimension, uint32_t seed);

// A cursor over the dimensions of one sample: index and seed fixed, each
// call takes the next dimension(s). Cheap to copy; holds no shared state.
class SampleStream {
 public:
  SampleStream(uint32_t index, uint32_t seed, uint32_t first_dimension = 0)
      : index_(index), seed_(seed), dimension_(first_dimension) {}
  float next_1d() { float v = sample_1d(index_, dimension_, seed_); dimension_ += 2; return v; }
  glm::vec2 next_2d() { glm::vec2 v = sample_2d(index_, dimension_, seed_); dimension_ += 2; return v; }
  uint32_t dimension() const { return dimension_; }

 private:
  uint32_t index_, seed_, dimension_;
};

}  // namespace igi
