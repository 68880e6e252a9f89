#include "scene/load_scene.h"

#include "scene/builtin_scenes.h"
#include "scene/gltf_loader.h"

namespace igi {

Scene load_scene(const std::string& name_or_path, std::vector<std::string>* warnings) {
  if (is_builtin_scene(name_or_path)) return make_builtin_scene(name_or_path);
  LoadedScene loaded = load_gltf(name_or_path);
  if (warnings) *warnings = std::move(loaded.warnings);
  return std::move(loaded.scene);
}

}  // namespace igi
