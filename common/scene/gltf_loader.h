#pragma once
// Reads a glTF 2.0 file (.gltf with its buffers and images, or .glb) into a
// Scene: triangles flattened into world space, materials mapped onto the
// renderer's material models, KHR_lights_punctual lights and the first
// perspective camera. The mapping lives next to each step:
//   gltf_nodes.h      node tree, lights, camera
//   gltf_geometry.h   primitives into world-space triangles
//   gltf_materials.h  materials (glTF's metallic-roughness model and the fast ones it reduces to)
//   gltf_textures.h   their textures, KHR_texture_transform, DDS maps
//   gltf_features.h   what is not modelled, reported once each
//   gltf_accessors.h  bounds-checked reads of the binary data
//
// Malformed or unreadable input throws SceneError whose message names the
// file and the offending element, e.g.
//   "scene.gltf: accessors[3] (POSITION of meshes[0].primitives[0]): count 1000
//    (stride 12, byteOffset 0) exceeds bufferView 2 (48 bytes)".
// The finished scene passes Scene::validate(): it has triangles and a light.
// Keeps no state between calls.
//
// External files (buffers, images) resolve only inside the scene's folder:
// a URI that leads elsewhere ("../x", "/etc/x", a symlink out) is refused, so
// a scene received from a peer cannot read the machine's other files.
#include <cstdint>
#include <span>
#include <string>
#include <optional>
#include <vector>

#include "scene/light_units.h"
#include "scene/scene.h"

namespace igi {

struct GltfOptions {
  // The sky, replacing the file's (the command line's, or the master's on a worker).
  std::optional<glm::vec3> environment;
  LightUnits light_units = LightUnits::Photometric;
  bool camera_given = false;  // the command line brings a camera: a file without one needs no notice of the framing one
  // --ignore-extension: read the file as if these extensions were absent
  // (gltf_json.h strip_extensions), each named in a warning with what is lost.
  std::vector<std::string> ignored_extensions{};
};

struct LoadedScene {
  Scene scene;
  // One line per feature the renderer left out or repaired, each naming the
  // file, the feature and what became of it.
  std::vector<std::string> warnings;
  // What the loader read or assumed that the user should know of, each a
  // line naming the file: the units its lights were read in, the camera and
  // light it supplied when the file has none.
  std::vector<std::string> notices;
  size_t file_lamps = 0;  // the lights the file gave (a supplied sun is not one of them)
};

// Binary when the file starts with the "glTF" magic or is named *.glb;
// JSON otherwise.
// External URIs resolve inside the file's folder. The environment (a
// constant sky) comes from the glTF scene's extras, {"environment": [r, g,
// b]}, unless `options.environment` is given: then that one.
//
// A file without a light (no punctual light, no emitter, no sky) gets a sun
// over the camera's shoulder, and one without a camera the framing camera
// of Scene::auto_camera(); each says so in `notices`.
LoadedScene load_gltf(const std::string& path, const GltfOptions& options = {});

// The same from bytes in memory (the fuzz targets, scenes off the wire).
// `name` stands for the file in messages and, like a path, says .glb when
// the bytes lack the magic. External URIs resolve inside `resource_dir`;
// with an empty `resource_dir` every external URI is refused.
LoadedScene load_gltf_memory(std::span<const uint8_t> bytes, const std::string& name,
                             const std::string& resource_dir = "", const GltfOptions& options = {});

}  // namespace igi
