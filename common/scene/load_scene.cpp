#include "scene/load_scene.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "scene/builtin_scenes.h"
#include "scene/gltf_loader.h"
#include "scene/obj_loader.h"

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

size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

// What a name that is neither a built-in scene nor a glTF file gets: the
// formats read and how to convert others, or the built-ins and the nearest.
void check_scene_name(const std::string& name) {
  namespace fs = std::filesystem;
  std::string extension = fs::path(name).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
  if (extension == ".gltf" || extension == ".glb" || extension == ".obj") return;
  std::error_code error;
  if (!extension.empty()) {
    if (!fs::exists(name, error)) return;  // load_gltf says "no such file"
    std::string how = "export it as glTF 2.0 (.glb) from a 3D tool; Blender reads " + extension +
                      " by File > Import and writes glTF by File > Export > glTF 2.0";
    if (extension == ".blend")
      how = "export it as glTF 2.0 with Blender: blender -b " + name +
            " --python-expr \"import bpy; bpy.ops.export_scene.gltf(filepath='scene.glb')\"";
    throw SceneError(name + ": igi-cluster reads glTF 2.0 (.gltf, .glb) and OBJ (.obj) scenes and its built-in scenes, not " +
                     extension + " files; " + how);
  }
  if (fs::exists(name, error)) return;  // a glTF file without an extension
  std::string list, nearest;
  size_t best = SIZE_MAX;
  for (const std::string& builtin : builtin_scene_names()) {
    list += (list.empty() ? "" : ", ") + builtin;
    const size_t d = edit_distance(name, builtin);
    if (d < best) best = d, nearest = builtin;
  }
  std::string message = name + ": no built-in scene of that name and no such file. Built-in scenes: " + list;
  if (best <= 2) message += ". Did you mean '" + nearest + "'?";
  throw SceneError(message);
}

}  // namespace

Scene load_scene(const std::string& name_or_path, const SceneOptions& options, SceneMessages* messages) {
  const std::optional<SkyChoice>& sky = options.sky;
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
  check_scene_name(name_or_path);
  LoadedScene loaded;
  if (is_obj_file(name_or_path)) {  // as glTF: the bytes workers are sent (scene/obj_loader.h)
    std::vector<std::string> obj_warnings;
    const std::vector<uint8_t> glb = obj_as_glb(name_or_path, &obj_warnings);
    loaded = load_gltf_memory(glb, name_or_path, "", {radiance, options.light_units, options.camera_given, options.ignored_extensions});
    loaded.warnings.insert(loaded.warnings.begin(), obj_warnings.begin(), obj_warnings.end());
  } else {
    loaded = load_gltf(name_or_path, {radiance, options.light_units, options.camera_given, options.ignored_extensions});
  }
  if (map) {
    loaded.scene.environment_map = std::move(map);
    loaded.scene.validate();  // a black map lights nothing
  }
  if (messages) *messages = {std::move(loaded.warnings), std::move(loaded.notices), loaded.file_lamps};
  return std::move(loaded.scene);
}

}  // namespace igi
