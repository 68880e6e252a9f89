#include "scene_cache.h"

#include <filesystem>
#include <stdexcept>
#include <unistd.h>

#include "io/file_bytes.h"
#include "scene/scene_file.h"

namespace igi {

namespace {

// A name the master sent, used as part of a file name: one path component,
// no way up. The protocol refuses these too; the cache does not rely on it.
bool is_plain_file_name(const std::string& name) {
  return !name.empty() && name != "." && name != ".." &&
         name.find_first_of(std::string("/\\\0", 3)) == std::string::npos;
}

}  // namespace

SceneCache::SceneCache(std::string cache_dir, std::vector<std::string> search_dirs)
    : cache_dir_(std::move(cache_dir)), search_dirs_(std::move(search_dirs)) {}

std::string SceneCache::cached_path(const std::string& file_name, uint64_t hash) const {
  return cache_dir_ + "/" + hash_hex(hash) + "-" + file_name;  // file_name: is_plain_file_name
}

std::optional<std::string> SceneCache::find(const std::string& file_name, uint64_t hash) const {
  if (!is_plain_file_name(file_name)) return std::nullopt;
  std::vector<std::string> candidates{cached_path(file_name, hash)};
  for (const std::string& dir : search_dirs_) candidates.push_back(dir + "/" + file_name);
  for (const std::string& path : candidates) {
    auto bytes = read_file_bytes(path);
    if (bytes && content_hash(*bytes) == hash) return path;
  }
  return std::nullopt;
}

std::string SceneCache::store(const protocol::SceneData& data) const {
  if (!is_plain_file_name(data.file_name))
    throw std::runtime_error("scene name '" + data.file_name + "' is not a plain file name: not stored");
  if (content_hash(data.bytes) != data.scene_hash)
    throw std::runtime_error("scene bytes for '" + data.file_name + "' do not match their hash " +
                             hash_hex(data.scene_hash));
  std::filesystem::create_directories(cache_dir_);
  const std::string path = cached_path(data.file_name, data.scene_hash);
  const std::string temporary = path + ".part-" + std::to_string(getpid());
  std::filesystem::remove(temporary);  // a leftover of a killed worker; remove() does not follow links
  write_new_file(temporary, data.bytes.data(), data.bytes.size(), 0644, Umask::applies);
  std::filesystem::rename(temporary, path);  // atomic: readers never see half a file
  return path;
}

}  // namespace igi
