#include "scene/load_scene.h"

#include "scene/builtin_scenes.h"
#include "scene/gltf_loader.h"

namespace igi {

namespace {

// The map, when the sky has one, before the scene is checked (a scene lit by it alone).
std::shared_ptr<const EnvironmentMap> load_map(const std::optional<SkyChoice>& sky) {
  if (!sky || sky->map.empty()) return nullptr;
  try {
    return std::make_shared<const EnvironmentMap>(EnvironmentMap::load(sky->map, sky->rotation));
  } catch (const std::exception& e) {
    throw SceneError(e.what());
  }
}

}  // namespace

Scene load_scene(const std::string& name_or_path, std::vector<std::string>* warnings,
                 const std::optional<SkyChoice>& sky) {
  std::shared_ptr<const EnvironmentMap> map = load_map(sky);
  const std::optional<glm::vec3> radiance = sky ? std::optional(sky->radiance) : std::nullopt;
  if (is_builtin_scene(name_or_path)) {
    Scene scene = make_builtin_scene(name_or_path);
    if (sky) {
      scene.environment = *radiance;
      scene.environment_map = std::move(map);
      scene.validate();
    }
    return scene;
  }
  LoadedScene loaded = load_gltf(name_or_path, radiance);
  if (map) {
    loaded.scene.environment_map = std::move(map);
    loaded.scene.validate();  // a black map lights nothing
  }
  if (warnings) *warnings = std::move(loaded.warnings);
  return std::move(loaded.scene);
}

}  // namespace igi
