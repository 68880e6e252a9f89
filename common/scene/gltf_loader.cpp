#include "scene/gltf_loader.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <tiny_gltf.h>

#include "io/file_bytes.h"
#include "sampling/warp.h"  // max_component
#include "scene/animation.h"
#include "scene/gltf_accessors.h"
#include "scene/gltf_animation.h"
#include "scene/gltf_diagnostics.h"
#include "scene/gltf_features.h"
#include "scene/gltf_geometry.h"
#include "scene/gltf_json.h"
#include "scene/gltf_materials.h"
#include "scene/gltf_nodes.h"

namespace igi {
namespace {

namespace fs = std::filesystem;

constexpr uint32_t kGlbMagic = 0x46546C67;      // "glTF"
constexpr uint32_t kChunkJson = 0x4E4F534A;     // "JSON"
constexpr uint32_t kChunkBin = 0x004E4942;      // "BIN\0"
constexpr size_t kGlbHeaderBytes = 12, kChunkHeaderBytes = 8;
// A file without a light gets a sun of this irradiance (W/m^2): a white
// diffuse face turned to it shows about 0.8 at exposure 1.
constexpr float kSuppliedSunIrradiance = 3.0f;

// 4 significant digits; whole numbers from 1000 to 1e9 in full (5435 cd, 27320 cd).
std::string format_number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, std::abs(x) >= 1e3 && std::abs(x) < 1e9 ? "%.0f" : "%.4g", x);
  return text;
}

std::string show(glm::vec3 p) {
  return "(" + format_number(p.x) + ", " + format_number(p.y) + ", " + format_number(p.z) + ")";
}


std::vector<unsigned char> read_file(const std::string& path) {
  std::error_code error;
  if (!fs::is_regular_file(path, error)) throw SceneError(path + ": no such file (or not a regular file)");
  const uintmax_t size = fs::file_size(path, error);
  // tinygltf takes 32-bit lengths; glTF caps .glb files at 4 GiB as well.
  if (error || size > UINT32_MAX)
    throw SceneError(path + ": cannot read the file's size, or it exceeds 4 GiB");
  std::ifstream in(path, std::ios::binary);
  std::vector<unsigned char> bytes(size);
  if (!in || !in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(size)))
    throw SceneError(path + ": cannot read the file");
  return bytes;
}

// tinygltf's file access for external buffers and images, confined to one
// folder. tinygltf tries each URI under the scene's folder and under ".";
// anything that resolves outside the folder is reported missing, and named
// in the error.
struct ResourceFolder {
  fs::path root;  // canonical; empty: no file may be read
  std::vector<std::string> refused;

  bool contains(const std::string& path) {
    std::error_code error;
    const bool inside = inside_folder(root.string(), path);
    const bool known = std::find(refused.begin(), refused.end(), path) != refused.end();
    if (!inside && !known && fs::exists(path, error)) refused.push_back(path);
    return inside;
  }
};

bool resource_exists(const std::string& path, void* folder) {
  std::error_code error;
  return static_cast<ResourceFolder*>(folder)->contains(path) && fs::is_regular_file(path, error);
}

std::string resource_path(const std::string& path, void*) { return path; }  // no ~ or $VAR expansion

bool read_resource(std::vector<unsigned char>* out, std::string* error, const std::string& path,
                   void* folder) {
  if (!static_cast<ResourceFolder*>(folder)->contains(path)) {
    *error = "outside the scene's folder";
    return false;
  }
  try {
    *out = read_file(path);
  } catch (const SceneError& e) {
    *error = e.what();
    return false;
  }
  return true;
}

bool refuse_writes(std::string* error, const std::string&, const std::vector<unsigned char>&, void*) {
  *error = "the loader writes no files";
  return false;
}

ResourceFolder resource_folder(const std::string& dir) {
  ResourceFolder folder;
  std::error_code error;
  if (!dir.empty()) folder.root = fs::weakly_canonical(dir, error);
  if (error) folder.root.clear();
  return folder;
}

uint32_t read_u32(std::span<const uint8_t> bytes, size_t at) {
  uint32_t value;  // GLB is little-endian, as is every machine this runs on
  std::memcpy(&value, bytes.data() + at, 4);
  return value;
}

bool is_glb(const std::string& path, std::span<const uint8_t> bytes) {
  if (bytes.size() >= 4 && read_u32(bytes, 0) == kGlbMagic) return true;
  std::string extension = fs::path(path).extension().string();
  for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
  return extension == ".glb";
}

// Checks the GLB framing before tinygltf reads it, so that a truncated file
// is reported as such and no chunk is read past the end of the bytes.
void check_glb(std::span<const uint8_t> bytes, const GltfDiagnostics& diag) {
  const size_t size = bytes.size();
  if (size < kGlbHeaderBytes + kChunkHeaderBytes)
    diag.fail("GLB header",
              "truncated: " + std::to_string(size) + " bytes, shorter than the headers (20 bytes)");
  if (read_u32(bytes, 0) != kGlbMagic) diag.fail("GLB header", "missing the 'glTF' magic");
  if (read_u32(bytes, 4) != 2)
    diag.fail("GLB header", "version " + std::to_string(read_u32(bytes, 4)) + ", expected 2");
  const size_t length = read_u32(bytes, 8);
  if (length > size)
    diag.fail("GLB header", "truncated: the header declares " + std::to_string(length) +
                                " bytes, the file has " + std::to_string(size));
  size_t at = kGlbHeaderBytes;
  for (int chunk = 0; at < length; ++chunk) {
    const std::string name = "GLB chunk " + std::to_string(chunk);
    if (length - at < kChunkHeaderBytes) diag.fail(name, "truncated chunk header");
    const size_t chunk_length = read_u32(bytes, at), type = read_u32(bytes, at + 4);
    if (chunk_length > length - at - kChunkHeaderBytes)
      diag.fail(name, "truncated: declares " + std::to_string(chunk_length) + " bytes, " +
                          std::to_string(length - at - kChunkHeaderBytes) + " remain");
    if (chunk == 0 && type != kChunkJson) diag.fail(name, "expected the JSON chunk first");
    if (chunk == 1 && type != kChunkBin) diag.fail(name, "expected a BIN chunk");
    at += kChunkHeaderBytes + chunk_length;
  }
}

// The JSON text: the file, or a .glb's first chunk (after check_glb, which
// leaves at least the headers; a chunk cut short is tinygltf's error).
std::span<const uint8_t> json_text(std::span<const uint8_t> bytes, bool binary) {
  if (!binary) return bytes;
  const size_t start = kGlbHeaderBytes + kChunkHeaderBytes;
  return bytes.subspan(start, std::min<size_t>(read_u32(bytes, kGlbHeaderBytes), bytes.size() - start));
}

// tinygltf would decode images while parsing, before anything has checked
// bufferViews against their buffers. Keep the encoded bytes of external and
// data-URI images instead; gltf_textures.cpp decodes the ones in use.
bool keep_encoded_image(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                        const unsigned char* bytes, int size, void*) {
  if (image->bufferView < 0 && bytes && size > 0) image->image.assign(bytes, bytes + size);
  image->as_is = true;
  return true;
}

// tinygltf reads every image the file names, used or not, and says so of
// each missing one (twice). Only the images materials use are decoded, and a
// missing one of those is an error of its own (gltf_textures.h): the others
// are counted into one notice (Sponza names DDS copies of all its textures).
void add_parser_warnings(const std::string& text, GltfDiagnostics& diag, size_t& missing_images) {
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("File not found", 0) == 0) continue;
    if (line.rfind("Failed to load external 'uri' for image", 0) == 0) {
      ++missing_images;
      continue;
    }
    if (!line.empty()) diag.warnings.push_back(diag.file + ": " + line);
  }
}

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

std::string trimmed(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  return text;
}

tinygltf::Model parse_model(std::span<const uint8_t> bytes, const std::string& resource_dir,
                            const std::vector<std::string>& ignored, GltfDiagnostics& diag, size_t& missing_images) {
  // tinygltf takes 32-bit lengths; glTF caps .glb files at 4 GiB as well.
  if (bytes.size() > UINT32_MAX) throw SceneError(diag.file + ": exceeds 4 GiB");
  const bool binary = is_glb(diag.file, bytes);
  if (binary) check_glb(bytes, diag);
  check_json_depth(json_text(bytes, binary), diag);  // before any parser recurses into it
  std::vector<std::string> removed;
  const std::optional<std::vector<uint8_t>> stripped = without_extensions(bytes, binary, ignored, &removed);
  if (stripped) bytes = *stripped;
  for (const std::string& name : removed)
    diag.warn_once("ignored " + name, name + " left out (--ignore-extension): " + extension_loss(name));
  check_unsigned_fields(json_text(bytes, binary), diag);
  ResourceFolder folder = resource_folder(resource_dir);
  tinygltf::TinyGLTF parser;
  parser.SetImageLoader(&keep_encoded_image, nullptr);
  parser.SetFsCallbacks({&resource_exists, &resource_path, &read_resource, &refuse_writes, &folder});
  const std::string base_dir = folder.root.string();
  tinygltf::Model model;
  std::string error, warning;
  bool ok = false;
  try {
    const unsigned size = unsigned(bytes.size());
    ok = binary ? parser.LoadBinaryFromMemory(&model, &error, &warning, bytes.data(), size, base_dir)
                : parser.LoadASCIIFromString(&model, &error, &warning,
                                             reinterpret_cast<const char*>(bytes.data()), size, base_dir);
  } catch (const std::exception& e) {
    error = e.what();
  }
  error = trimmed(error);
  for (const std::string& path : folder.refused)
    error += (error.empty() ? "" : "; ") + path + " refused: outside the scene's folder";
  if (!ok) throw SceneError(diag.file + ": " + (error.empty() ? "not a valid glTF file" : error));
  add_parser_warnings(warning, diag, missing_images);
  for (const std::string& path : folder.refused)
    diag.warnings.push_back(diag.file + ": " + path + " refused: outside the scene's folder");
  return model;
}

// Node transforms may carry finite object-space positions out of range.
void check_world_extent(const Scene& scene, const GltfDiagnostics& diag) {
  for (size_t i = 0; i < scene.positions.size(); ++i) {
    const glm::vec3 p = scene.positions[i];
    if (glm::any(glm::greaterThan(glm::abs(p), glm::vec3(float(kMaxCoordinate)))) || !finite(p))
      diag.fail("meshes", "world-space vertex " + std::to_string(i) + " (after node transforms) at (" +
                              std::to_string(p.x) + ", " + std::to_string(p.y) + ", " + std::to_string(p.z) +
                              "), expected coordinates within +-1e15 m");
  }
}

// Channels keep the nodes the walk reached (an animation may target a node
// of another glTF scene), renumbered to the moving nodes.
std::shared_ptr<const SceneAnimation> make_animation(std::vector<AnimationChannel> channels,
                                                     FlattenedNodes& nodes, std::vector<DynamicPart> parts,
                                                     const Scene& scene, const GltfDiagnostics& diag) {
  auto animation = std::make_shared<SceneAnimation>();
  for (AnimationChannel& channel : channels) {
    const int node = nodes.pose_node_of[channel.node];
    if (node < 0) continue;
    channel.node = uint32_t(node);
    animation->duration = std::max(animation->duration, channel.times.back());
    animation->channels.push_back(std::move(channel));
  }
  animation->nodes = std::move(nodes.pose_nodes);
  animation->parts = std::move(parts);
  animation->rest_lights = scene.lights;
  animation->light_node = std::move(nodes.light_pose_node);
  animation->camera_node = nodes.camera_pose_node;
  if (const auto out = animation->check_extent(kMaxCoordinate)) {
    std::string why = (out->key ? "at key time " : "between keys, at time ") + std::to_string(out->time) + " " + out->what;
    if (const auto p = out->position)
      why += " reaches (" + std::to_string(p->x) + ", " + std::to_string(p->y) + ", " + std::to_string(p->z) +
             "), expected coordinates within +-1e15 m";
    diag.fail("animations", why);
  }
  return animation;
}

// The scene's extras {"environment": "sky.hdr", "environment_rotation": 30}:
// an environment map in the scene's folder (scene/environment_map.h), turned
// by that many degrees about +y (0 when absent).
void read_environment_map(const tinygltf::Value& extras, const std::string& resource_dir, GltfDiagnostics& diag,
                          Scene& scene) {
  const std::string name = extras.Get("environment").Get<std::string>();
  float rotation = 0.0f;
  if (extras.Has("environment_rotation")) {
    const tinygltf::Value& r = extras.Get("environment_rotation");
    if (!r.IsNumber() || !(std::abs(r.GetNumberAsDouble()) <= 360.0))
      diag.fail("scenes", "extras.environment_rotation must be degrees within +-360");
    rotation = float(r.GetNumberAsDouble());
  }
  const std::string path = (fs::path(resource_dir) / name).string();
  ResourceFolder folder = resource_folder(resource_dir);
  if (!folder.contains(path)) diag.fail("scenes", "extras.environment: " + name + " is outside the scene's folder");
  try {
    scene.environment_map = std::make_shared<const EnvironmentMap>(EnvironmentMap::load(path, rotation));
  } catch (const std::exception& e) {
    diag.fail("scenes", std::string("extras.environment: ") + e.what());
  }
}

// The scene's extras {"environment": [r, g, b]}: a constant sky's radiance
// (gltf_writer.cpp writes it), or the name of a map (read_environment_map,
// then the radiance is 1, 1, 1: the map's own); none when absent.
glm::vec3 read_environment(const tinygltf::Model& model, const std::string& resource_dir, GltfDiagnostics& diag,
                           Scene& scene) {
  if (model.scenes.empty()) return glm::vec3(0.0f);
  const tinygltf::Value& extras = model.scenes[size_t(std::max(0, model.defaultScene)) % model.scenes.size()].extras;
  if (!extras.IsObject() || !extras.Has("environment")) return glm::vec3(0.0f);
  const tinygltf::Value& v = extras.Get("environment");
  if (v.IsString()) {
    read_environment_map(extras, resource_dir, diag, scene);
    return glm::vec3(1.0f);
  }
  glm::vec3 c(0.0f);
  bool ok = v.IsArray() && v.ArrayLen() == 3;
  for (int i = 0; ok && i < 3; ++i) {
    ok = v.Get(i).IsNumber();
    if (ok) c[i] = float(v.Get(i).GetNumberAsDouble());
  }
  if (!ok) diag.fail("scenes", "extras.environment must be three numbers [r, g, b] or a map's file name");
  return c;  // finite and >= 0: Scene::validate
}

// The line that says how the file's lights (already in W/sr and W/m^2) were read.
std::string light_units_notice(LightUnits units, const GltfDiagnostics& diag, const std::vector<PunctualLight>& lights) {
  const PunctualLight* brightest = &lights[0];
  for (const PunctualLight& light : lights)
    if (max_component(light.intensity) > max_component(brightest->intensity)) brightest = &light;
  const double radiometric = max_component(brightest->intensity);
  const bool directional = brightest->type == LightType::Directional;
  const std::string count = std::to_string(lights.size()) + (lights.size() == 1 ? " lamp" : " lamps");
  const std::string unit = directional ? " W/m^2" : " W/sr";
  if (units == LightUnits::Radiometric)
    return diag.file + ": " + count + " read as W/sr and W/m^2 (--light-units radiometric); the brightest " +
           format_number(radiometric) + unit;
  return diag.file + ": " + count + " in glTF's units, candela and lux, read at " + format_number(kLumensPerWatt) +
         " lm/W: the brightest " + format_number(radiometric * kLumensPerWatt) + (directional ? " lux = " : " cd = ") +
         format_number(radiometric) + unit + " (--light-units radiometric reads them as W/sr and W/m^2)";
}

// A file without a light or a camera (Blender exports neither by default):
// a sun over the camera's shoulder, and the framing camera, each named.
void supply_light_and_camera(const GltfDiagnostics& diag, bool camera_given, Scene& scene,
                             std::vector<std::string>& notices) {
  if (!scene.has_light()) {
    const Camera camera = scene.camera_or_auto();
    const glm::vec3 across = glm::cross(camera.forward, camera.up);
    const glm::vec3 right = glm::length(across) > 1e-6f ? glm::normalize(across) : glm::vec3(1.0f, 0.0f, 0.0f);
    const glm::vec3 up = glm::cross(right, camera.forward);
    PunctualLight sun;
    sun.type = LightType::Directional;
    sun.direction = glm::normalize(camera.forward - 0.4f * up + 0.3f * right);  // from above, left and behind
    sun.intensity = glm::vec3(kSuppliedSunIrradiance);
    scene.lights.push_back(sun);
    notices.push_back(diag.file + ": no light (no lamp, no emissive material, no sky): lit by a sun of " +
                      format_number(kSuppliedSunIrradiance) +
                      " W/m^2 from over the camera's shoulder. Export the lamps with the file "
                      "(Blender: Include > Punctual Lights) or light it with --environment 1,1,1");
  }
  if (!scene.camera && !camera_given) {
    const Camera camera = scene.auto_camera();
    notices.push_back(diag.file + ": no camera: framing the scene from " + show(camera.position) +
                      ", looking at its centre from the side its lights face (--camera FILE, or the window, "
                      "picks another)");
  }
}

// Scene::validate names the scene, not the file: prefix the file.
void validate_scene(const Scene& scene, const GltfDiagnostics& diag) {
  try {
    scene.validate();
  } catch (const SceneError& e) {
    throw SceneError(diag.file + ": " + e.what());
  }
}

}  // namespace

LoadedScene load_gltf(const std::string& path, const GltfOptions& options) {
  const std::string folder = fs::path(path).parent_path().string();
  return load_gltf_memory(read_file(path), path, folder.empty() ? "." : folder, options);
}

LoadedScene load_gltf_memory(std::span<const uint8_t> bytes, const std::string& name,
                             const std::string& resource_dir, const GltfOptions& options) {
  GltfDiagnostics diag;
  diag.file = name;
  size_t missing_images = 0;
  const tinygltf::Model model = parse_model(bytes, resource_dir, options.ignored_extensions, diag, missing_images);
  check_required_extensions(model, diag);
  check_buffer_views(model, diag);
  warn_unsupported_features(model, diag);

  LoadedScene loaded;
  Scene& scene = loaded.scene;
  convert_materials(model, diag, scene);
  if (missing_images > 0)
    diag.notice_once("missing images", std::to_string(missing_images) + " of the file's " +
                                           std::to_string(model.images.size()) +
                                           " images are not there; no material reads them");
  std::vector<AnimationChannel> channels = read_gltf_animations(model, diag);
  std::vector<bool> animated(model.nodes.size(), false);
  for (const AnimationChannel& channel : channels) animated[channel.node] = true;
  const bool photometric = options.light_units == LightUnits::Photometric;
  FlattenedNodes nodes = flatten_nodes(model, animated, photometric ? 1.0 / kLumensPerWatt : 1.0, diag);
  std::vector<DynamicPart> parts = add_mesh_instances(model, nodes.instances, diag, scene);
  check_world_extent(scene, diag);
  scene.lights = std::move(nodes.lights);
  loaded.file_lamps = scene.lights.size();
  if (!scene.lights.empty()) loaded.notices.push_back(light_units_notice(options.light_units, diag, scene.lights));
  scene.camera = nodes.camera;
  if (!nodes.pose_nodes.empty()) scene.animation = make_animation(std::move(channels), nodes, std::move(parts), scene, diag);
  scene.name = nodes.scene_name.empty() ? fs::path(name).stem().string() : nodes.scene_name;
  // The command line's sky replaces the file's (a worker's copy: the master's sky, its map sent apart).
  scene.environment = options.environment ? *options.environment : read_environment(model, resource_dir, diag, scene);
  if (!scene.triangles.empty()) supply_light_and_camera(diag, options.camera_given, scene, loaded.notices);
  validate_scene(scene, diag);
  loaded.warnings = std::move(diag.warnings);
  loaded.notices.insert(loaded.notices.end(), diag.notices.begin(), diag.notices.end());
  return loaded;
}

}  // namespace igi
