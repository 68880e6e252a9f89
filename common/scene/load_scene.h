#pragma once
// One entry point for every command: a built-in scene name or a glTF path.
#include <optional>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace igi {

// Throws SceneError with a message naming the file or scene on failure.
// Warnings about glTF features that were mapped or ignored go to `warnings`.
// `environment`, when given, replaces the scene's own sky (--environment).
Scene load_scene(const std::string& name_or_path, std::vector<std::string>* warnings = nullptr,
                 std::optional<glm::vec3> environment = std::nullopt);

}  // namespace igi
