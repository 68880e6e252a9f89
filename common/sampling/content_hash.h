#pragma once
// Content hashes: 64-bit XXH3 over bytes. What workers compare bit for bit
// (VPL sets, light trees, photon maps: the frame_state_hash the master checks
// by quorum) and the scene file's hash on the wire. XXH3 is fast (several
// GB/s) and spreads well, but is not cryptographic: it catches corruption and
// mix-ups, not a forgery (see the README's threat model).
#include <cstddef>
#include <cstdint>
#include <type_traits>

#define XXH_STATIC_LINKING_ONLY  // XXH3_state_t by value, not through XXH3_createState
#include <xxhash.h>

namespace igi {

inline uint64_t content_hash(const void* data, size_t size) { return XXH3_64bits(data, size); }

// The same hash over a stream of pieces: equal to content_hash of the pieces
// laid end to end.
class ContentHasher {
 public:
  ContentHasher() { XXH3_64bits_reset(&state_); }
  ContentHasher(const ContentHasher&) = delete;
  ContentHasher& operator=(const ContentHasher&) = delete;

  void add_bytes(const void* data, size_t size) { XXH3_64bits_update(&state_, data, size); }
  // A plain value's bytes; it must have no padding, or the hash would read it.
  template <class T>
  void add(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>, "hash only plain values");
    add_bytes(&value, sizeof value);
  }
  uint64_t value() const { return XXH3_64bits_digest(&state_); }

 private:
  XXH3_state_t state_;
};

// One hash of two: the order matters.
inline uint64_t combine_content_hashes(uint64_t first, uint64_t second) {
  const uint64_t both[2] = {first, second};
  return content_hash(both, sizeof both);
}

}  // namespace igi
