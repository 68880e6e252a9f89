#include "sampling/sobol.h"

#include "sampling/hash.h"

namespace igi {

static uint32_t reverse_bits(uint32_t v) {
  v = __builtin_bswap32(v);
  v = ((v >> 1) & 0x55555555u) | ((v & 0x55555555u) << 1);
  v = ((v >> 2) & 0x33333333u) | ((v & 0x33333333u) << 2);
  return ((v >> 4) & 0x0f0f0f0fu) | ((v & 0x0f0f0f0fu) << 4);
}

uint32_t sobol_dim0(uint32_t index) { return reverse_bits(index); }

namespace {

// Generator matrix columns of the second dimension: v_0 = 2^31,
// v_{k+1} = v_k ^ (v_k >> 1). The product with an index is a XOR over its
// set bits, so it splits into one table per index byte.
struct SobolDim1Tables {
  uint32_t byte[4][256];
  constexpr SobolDim1Tables() : byte{} {
    uint32_t column[32] = {};
    column[0] = 1u << 31;
    for (int k = 1; k < 32; ++k) column[k] = column[k - 1] ^ (column[k - 1] >> 1);
    for (int b = 0; b < 4; ++b)
      for (uint32_t value = 0; value < 256; ++value)
        for (int bit = 0; bit < 8; ++bit)
          if (value & (1u << bit)) byte[b][value] ^= column[8 * b + bit];
  }
};
constexpr SobolDim1Tables kSobolDim1;

}  // namespace

uint32_t sobol_dim1(uint32_t index) {
  return kSobolDim1.byte[0][index & 255] ^ kSobolDim1.byte[1][(index >> 8) & 255] ^
         kSobolDim1.byte[2][(index >> 16) & 255] ^ kSobolDim1.byte[3][index >> 24];
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
