#include "scene/scene_file.h"

#include <cstdio>
#include <fstream>
#include <iterator>

#include "sampling/content_hash.h"

namespace igi {

std::optional<std::vector<uint8_t>> read_file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) return std::nullopt;
  return bytes;
}

uint64_t content_hash(const std::vector<uint8_t>& bytes) { return content_hash(bytes.data(), bytes.size()); }

std::string hash_hex(uint64_t hash) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash));
  return text;
}

}  // namespace igi
