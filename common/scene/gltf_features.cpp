#include "scene/gltf_features.h"

#include <algorithm>
#include <iterator>
#include <set>

#include <tiny_gltf.h>

namespace igi {
namespace {

// MSFT_texture_dds: a texture reads its core PNG or JPEG source, its DDS
// image only where it has none (BC4, the single-channel maps
// AMD_split_roughnessMetallic points at; scene/gltf_textures.h).
constexpr const char* kSupported[] = {"KHR_lights_punctual", "KHR_materials_transmission", "KHR_materials_ior",
                                      "KHR_materials_emissive_strength", "KHR_materials_specular",
                                      "KHR_texture_transform", "MSFT_texture_dds", "AMD_split_roughnessMetallic"};

bool supported(const std::string& extension) {
  return std::find(std::begin(kSupported), std::end(kSupported), extension) != std::end(kSupported);
}

bool starts_with(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

}  // namespace

// What the renderer does instead of the extension, for the warning.
std::string extension_loss(const std::string& extension) {
  if (extension == "KHR_texture_transform") return "texture coordinates are used untransformed";
  if (extension == "MSFT_texture_dds") return "textures read only their core PNG or JPEG images";
  if (extension == "AMD_split_roughnessMetallic") return "roughness and metallic are the materials' factors, untextured";
  if (starts_with(extension, "KHR_materials_") || starts_with(extension, "EXT_materials_"))
    return "materials are read from their core metallic-roughness parameters";
  if (extension == "KHR_draco_mesh_compression" || extension == "EXT_meshopt_compression")
    return "compressed data cannot be read, only uncompressed accessors load";
  if (extension == "KHR_mesh_quantization") return "only FLOAT positions and normals load";
  if (extension == "KHR_texture_basisu" || extension == "EXT_texture_webp" || extension == "MSFT_texture_dds")
    return "textures use their core image source if they have one";
  if (extension == "EXT_mesh_gpu_instancing") return "each node is placed once, without its instances";
  return "the file is read as if the extension were absent";
}

namespace {

using Names = std::set<std::string>;

void collect(const tinygltf::ExtensionMap& extensions, Names& names) {
  for (const auto& entry : extensions) names.insert(entry.first);
}

template <typename T>
void collect_all(const std::vector<T>& objects, Names& names) {
  for (const T& object : objects) collect(object.extensions, names);
}

void collect_materials(const tinygltf::Model& model, Names& names) {
  for (const tinygltf::Material& m : model.materials) {
    collect(m.extensions, names);
    collect(m.pbrMetallicRoughness.extensions, names);
    collect(m.pbrMetallicRoughness.baseColorTexture.extensions, names);
    collect(m.pbrMetallicRoughness.metallicRoughnessTexture.extensions, names);
    collect(m.normalTexture.extensions, names);
    collect(m.occlusionTexture.extensions, names);
    collect(m.emissiveTexture.extensions, names);
  }
}

// Every extension named anywhere in the file, declared or not.
Names extensions_in(const tinygltf::Model& model) {
  Names names(model.extensionsUsed.begin(), model.extensionsUsed.end());
  names.insert(model.extensionsRequired.begin(), model.extensionsRequired.end());
  collect(model.extensions, names);
  collect(model.asset.extensions, names);
  collect_all(model.accessors, names);
  collect_all(model.animations, names);
  collect_all(model.buffers, names);
  collect_all(model.bufferViews, names);
  collect_all(model.meshes, names);
  for (const tinygltf::Mesh& mesh : model.meshes) collect_all(mesh.primitives, names);
  collect_all(model.nodes, names);
  collect_all(model.textures, names);
  collect_all(model.images, names);
  collect_all(model.skins, names);
  collect_all(model.samplers, names);
  collect_all(model.cameras, names);
  collect_all(model.scenes, names);
  collect_all(model.lights, names);
  collect_materials(model, names);
  return names;
}

bool has_morph_targets(const tinygltf::Model& model) {
  for (const tinygltf::Mesh& mesh : model.meshes) {
    if (!mesh.weights.empty()) return true;
    for (const tinygltf::Primitive& primitive : mesh.primitives)
      if (!primitive.targets.empty()) return true;
  }
  return std::any_of(model.nodes.begin(), model.nodes.end(),
                     [](const tinygltf::Node& node) { return !node.weights.empty(); });
}

// Required ones have been refused already (check_required_extensions).
void warn_extensions(const tinygltf::Model& model, GltfDiagnostics& diag) {
  for (const std::string& extension : extensions_in(model))
    if (!supported(extension))
      diag.warn_once("extension " + extension, "extension " + extension + " ignored: " + extension_loss(extension));
}

}  // namespace

void check_required_extensions(const tinygltf::Model& model, const GltfDiagnostics& diag) {
  for (size_t i = 0; i < model.extensionsRequired.size(); ++i) {
    const std::string& extension = model.extensionsRequired[i];
    if (supported(extension)) continue;
    diag.fail(gltf_element("extensionsRequired", i),
              extension + " is required but not supported, so the file cannot be read as meant; "
                          "--ignore-extension " + extension + " loads it anyway (" + extension_loss(extension) + ")");
  }
}

void warn_unsupported_features(const tinygltf::Model& model, GltfDiagnostics& diag) {
  const bool skinned = std::any_of(model.nodes.begin(), model.nodes.end(),
                                   [](const tinygltf::Node& node) { return node.skin >= 0; });
  if (!model.skins.empty() || skinned)
    diag.warn_once("skins", "skins ignored: skinned meshes are rendered in their bind pose");
  if (has_morph_targets(model))
    diag.warn_once("morph targets", "morph targets ignored: meshes keep their base shape");
  if (model.scenes.size() > 1)
    diag.warn_once("scenes", std::to_string(model.scenes.size()) +
                                 " scenes in the file: only the default scene is loaded");
  warn_extensions(model, diag);
  if (extensions_in(model).count("MSFT_texture_dds"))
    diag.notice_once("MSFT_texture_dds", "MSFT_texture_dds: textures read their core PNG or JPEG images, and a "
                                         "DDS only where a texture has none (BC4 single-channel maps)");
}

}  // namespace igi
