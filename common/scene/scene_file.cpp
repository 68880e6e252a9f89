#include "scene/scene_file.h"

#include <cstdio>

#include "sampling/content_hash.h"

namespace igi {

uint64_t content_hash(const std::vector<uint8_t>& bytes) { return content_hash(bytes.data(), bytes.size()); }

std::string hash_hex(uint64_t hash) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash));
  return text;
}

}  // namespace igi
