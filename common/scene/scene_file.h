#pragma once
// Scene files as bytes: what the master sends and what workers check by hash.
#include <cstdint>
#include <string>
#include <vector>

#include "io/file_bytes.h"  // read_file_bytes

namespace igi {

// XXH3-64 of a file's bytes: the scene's content hash on the wire.
uint64_t content_hash(const std::vector<uint8_t>& bytes);
std::string hash_hex(uint64_t hash);

}  // namespace igi
