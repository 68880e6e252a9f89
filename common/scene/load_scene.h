#pragma once
// One entry point for every command: a built-in scene name or a glTF path.
#include <optional>
#include <string>
#include <vector>

#include "scene/gltf_loader.h"
#include "scene/scene.h"

namespace igi {

// A sky from the command line (--environment R,G,B or FILE,
// --environment-scale, --environment-rotation): a constant radiance, or an
// equirectangular map (scene/environment_map.h) times `radiance`.
struct SkyChoice {
  glm::vec3 radiance{1.0f};
  std::string map;        // the map's path; empty: a constant sky
  float rotation = 0.0f;  // the map's, degrees about +y
};

// How the command line asks a scene to be read; a worker reads the
// master's scene as the master's Welcome says.
struct SceneOptions {
  std::optional<SkyChoice> sky;  // replaces the scene's own (--environment)
  LightUnits light_units = LightUnits::Photometric;  // a glTF file's lamps (--light-units)
  bool camera_given = false;  // --camera FILE: a file without a camera gets no notice of the framing one
  std::vector<std::string> ignored_extensions{};  // --ignore-extension (gltf_loader.h GltfOptions)
};

// What loading a file said (gltf_loader.h's LoadedScene): features mapped or
// ignored, and what it read or assumed (units, a supplied camera or light).
struct SceneMessages {
  std::vector<std::string> warnings, notices;
  size_t file_lamps = 0;  // KHR_lights_punctual lamps read (--light-units applies to them)
};

// Throws SceneError with a message naming the file or scene on failure.
Scene load_scene(const std::string& name_or_path, const SceneOptions& options = {},
                 SceneMessages* messages = nullptr);

}  // namespace igi
