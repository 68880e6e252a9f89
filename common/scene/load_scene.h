#pragma once
// One entry point for every command: a built-in scene name or a glTF path.
#include <optional>
#include <string>
#include <vector>

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

// Throws SceneError with a message naming the file or scene on failure.
// Warnings about glTF features that were mapped or ignored go to `warnings`.
// `sky`, when given, replaces the scene's own (--environment).
Scene load_scene(const std::string& name_or_path, std::vector<std::string>* warnings = nullptr,
                 const std::optional<SkyChoice>& sky = std::nullopt);

}  // namespace igi
