#pragma once
// Integer hashes that turn coordinates into independent seeds. Every random
// number in the renderer is a pure function of such hashed coordinates.
#include <cstdint>

namespace igi {

// Murmur3 finaliser: a full-avalanche 32-bit mix.
constexpr uint32_t mix32(uint32_t h) {
  h ^= h >> 16; h *= 0x85ebca6bu;
  h ^= h >> 13; h *= 0xc2b2ae35u;
  h ^= h >> 16;
  return h;
}

constexpr uint32_t hash_combine(uint32_t seed, uint32_t value) {
  return mix32(seed ^ (value + 0x9e3779b9u + (seed << 6) + (seed >> 2)));
}

constexpr uint32_t hash(uint32_t a, uint32_t b) { return hash_combine(mix32(a), b); }
constexpr uint32_t hash(uint32_t a, uint32_t b, uint32_t c) { return hash_combine(hash(a, b), c); }

}  // namespace igi
