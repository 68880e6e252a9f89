#include "scene_cache.h"

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <unistd.h>

#include "scene/scene_file.h"

namespace igi {

SceneCache::SceneCache(std::string cache_dir, std::vector<std::string> search_dirs)
    : cache_dir_(std::move(cache_dir)), search_dirs_(std::move(search_dirs)) {}

std::string SceneCache::cached_path(const std::string& file_name, uint64_t hash) const {
  // The protocol has already refused names with '/', '\\' or "..".
  return cache_dir_ + "/" + hash_hex(hash) + "-" + file_name;
}

std::optional<std::string> SceneCache::find(const std::string& file_name, uint64_t hash) const {
  std::vector<std::string> candidates{cached_path(file_name, hash)};
  for (const std::string& dir : search_dirs_) candidates.push_back(dir + "/" + file_name);
  for (const std::string& path : candidates) {
    auto bytes = read_file_bytes(path);
    if (bytes && content_hash(*bytes) == hash) return path;
  }
  return std::nullopt;
}

std::string SceneCache::store(const protocol::SceneData& data) const {
  if (content_hash(data.bytes) != data.scene_hash)
    throw std::runtime_error("scene bytes for '" + data.file_name + "' do not match their hash " +
                             hash_hex(data.scene_hash));
  std::filesystem::create_directories(cache_dir_);
  const std::string path = cached_path(data.file_name, data.scene_hash);
  const std::string temporary = path + ".part-" + std::to_string(getpid());
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data.bytes.data()), std::streamsize(data.bytes.size()));
    if (!out) throw std::runtime_error("cannot write " + temporary);
  }
  std::filesystem::rename(temporary, path);  // atomic: readers never see half a file
  return path;
}

}  // namespace igi
