#pragma once
// Where a worker finds the scene the master names by content hash: a file in
// one of its search folders whose bytes hash right, or its cache folder.
// Bytes received from a master are written only inside the cache folder,
// under their hash, and only after the hash checks out.
#include <optional>
#include <string>
#include <vector>

#include "protocol/messages.h"

namespace igi {

class SceneCache {
 public:
  SceneCache(std::string cache_dir, std::vector<std::string> search_dirs);
  // A readable file with the wanted name and hash, or nothing.
  std::optional<std::string> find(const std::string& file_name, uint64_t hash) const;
  // Checks the bytes against their hash and stores them; returns the path.
  // Throws std::runtime_error when the hash is wrong or the write fails.
  std::string store(const protocol::SceneData& data) const;

 private:
  std::string cached_path(const std::string& file_name, uint64_t hash) const;
  std::string cache_dir_;
  std::vector<std::string> search_dirs_;
};

}  // namespace igi
