#include "scene/load_scene.h"

#include "scene/builtin_scenes.h"
#include "scene/gltf_loader.h"

namespace igi {

Scene load_scene(const std::string& name_or_path, std::vector<std::string>* warnings,
                 std::optional<glm::vec3> environment) {
  if (is_builtin_scene(name_or_path)) {
    Scene scene = make_builtin_scene(name_or_path);
    if (environment) {
      scene.environment = *environment;
      scene.validate();
    }
    return scene;
  }
  LoadedScene loaded = load_gltf(name_or_path, environment);
  if (warnings) *warnings = std::move(loaded.warnings);
  return std::move(loaded.scene);
}

}  // namespace igi
