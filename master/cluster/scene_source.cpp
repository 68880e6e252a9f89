#include "cluster/scene_source.h"

#include <cstdio>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <utility>

#include "io/file_bytes.h"
#include "protocol/codec.h"
#include "sampling/content_hash.h"
#include "scene/builtin_scenes.h"
#include "scene/gltf_pack.h"
#include "scene/scene_file.h"

namespace igi {

zmq::message_t shared_frame(const std::shared_ptr<const std::vector<uint8_t>>& bytes) {
  auto* keep = new std::shared_ptr<const std::vector<uint8_t>>(bytes);
  auto release = [](void*, void* hint) { delete static_cast<std::shared_ptr<const std::vector<uint8_t>>*>(hint); };
  return zmq::message_t(const_cast<uint8_t*>(bytes->data()), bytes->size(), release, keep);
}

SceneSource make_scene_source(const std::string& scene) {
  if (is_builtin_scene(scene)) {
    SceneSource builtin;
    builtin.name = scene;
    return builtin;
  }
  SceneFile file = scene_file_for_workers(scene);  // a .gltf with files beside it: packed into one .glb
  if (file.packed)
    std::fprintf(stderr, "igi-master: %s goes to workers as %s, its buffers and images packed in\n", scene.c_str(),
                 file.name.c_str());
  SceneSource source;
  source.name = file.name;
  source.hash = content_hash(file.bytes);
  source.size = file.bytes.size();
  protocol::SceneData data{source.hash, source.name, std::move(file.bytes)};
  source.message = std::make_shared<const std::vector<uint8_t>>(protocol::encode(data));
  return source;
}

void add_environment_map(SceneSource& source, const std::string& path, float rotation) {
  std::optional<std::vector<uint8_t>> bytes = read_file_bytes(path);
  if (!bytes) throw std::runtime_error("cannot read the environment map " + path);
  source.map_name = std::filesystem::path(path).filename().string();
  source.map_hash = content_hash(*bytes);
  source.map_size = bytes->size();
  source.map_rotation = rotation;
  protocol::SceneData data{source.map_hash, source.map_name, std::move(*bytes)};
  source.map_message = std::make_shared<const std::vector<uint8_t>>(protocol::encode(data));
}

}  // namespace igi
