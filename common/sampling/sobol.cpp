#include "sampling/sobol.h"

#include "sampling/hash.h"

namespace igi {

static uint32_t reverse_bits(uint32_t v) {
  v = ((v >> 1) & 0x55555555u) | ((v & 0x55555555u) << 1);
  v = ((v >> 2) & 0x33333333u) | ((v & 0x33333333u) << 2);
  v = ((v >> 4) & 0x0f0f0f0fu) | ((v & 0x0f0f0f0fu) << 4);
  v = ((v >> 8) & 0x00ff00ffu) | ((v & 0x00ff00ffu) << 8);
  return (v >> 16) | (v << 16);
}

uint32_t sobol_dim0(uint32_t index) { return reverse_bits(index); }

uint32_t sobol_dim1(uint32_t index) {
  // Generator matrix columns: v_0 = 2^31, v_{k+1} = v_k ^ (v_k >> 1).
  uint32_t result = 0;
  for (uint32_t v = 1u << 31; index; index >>= 1, v ^= v >> 1)
    if (index & 1u) result ^= v;
  return result;
}

// Laine-Karras style hash in reversed bit order: bit k of the output depends
// only on bits more significant than k of the input (Burley 2020, fig. 5).
uint32_t owen_scramble(uint32_t value, uint32_t seed) {
  uint32_t v = reverse_bits(value);
  v ^= v * 0x3d20adeau;
  v += seed;
  v *= (seed >> 16) | 1u;
  v ^= v * 0x05526c56u;
  v ^= v * 0x53a22864u;
  return reverse_bits(v);
}

static float to_unit_float(uint32_t fixed) {
  // 24 significant bits so the result is strictly below 1.
  return static_cast<float>(fixed >> 8) * 0x1p-24f;
}

glm::vec2 sample_2d(uint32_t index, uint32_t dimension, uint32_t seed) {
  uint32_t pair_seed = hash(seed, dimension >> 1);
  // Shuffle the index (an Owen scramble in reversed order permutes every
  // aligned power-of-two block onto a block), then scramble each coordinate.
  uint32_t shuffled = owen_scramble(index, pair_seed);
  uint32_t x = owen_scramble(sobol_dim0(shuffled), mix32(pair_seed ^ 0xa511e9b3u));
  uint32_t y = owen_scramble(sobol_dim1(shuffled), mix32(pair_seed ^ 0x63d83595u));
  return {to_unit_float(x), to_unit_float(y)};
}

float sample_1d(uint32_t index, uint32_t dimension, uint32_t seed) {
  return sample_2d(index, dimension & ~1u, seed)[dimension & 1u];
}

}  // namespace igi
