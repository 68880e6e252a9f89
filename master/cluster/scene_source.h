#pragma once
// What workers are told about the scene, and its bytes for those without it:
// encoded once as a SceneData message and sent without a copy (shared_frame()).
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <zmq.hpp>

#include "scene/light_units.h"

namespace igi {

struct SceneSource {
  std::string name;        // built-in name or file name
  uint64_t hash = 0;       // 0 for built-in scenes
  uint64_t size = 0;       // bytes of the file
  std::shared_ptr<const std::vector<uint8_t>> message;  // the encoded SceneData; null for built-in scenes
  glm::vec3 environment{0.0f};  // the sky the master's scene stands under (Welcome carries it)
  // Its map, when it has one: workers ask for it by hash as for the scene.
  std::string map_name;
  uint64_t map_hash = 0, map_size = 0;
  float map_rotation = 0.0f;
  std::shared_ptr<const std::vector<uint8_t>> map_message;  // the encoded SceneData
  LightUnits light_units = LightUnits::Photometric;  // how the file's lamps are read (Welcome carries it)
};

// Reads a scene file (or names a built-in scene) and encodes what workers may ask for.
SceneSource make_scene_source(const std::string& scene);
// Reads the environment map `path` into `source`, for workers to ask for.
void add_environment_map(SceneSource& source, const std::string& path, float rotation);

// The encoded bytes handed to ZeroMQ without a copy; zmq drops the reference when sent.
zmq::message_t shared_frame(const std::shared_ptr<const std::vector<uint8_t>>& bytes);

}  // namespace igi
