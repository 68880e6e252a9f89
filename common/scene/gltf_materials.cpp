#include "scene/gltf_materials.h"

#include <algorithm>
#include <cmath>

#include <tiny_gltf.h>

#include "scene/gltf_textures.h"

namespace igi {
namespace {

const tinygltf::Value* find_extension(const tinygltf::ExtensionMap& extensions, const char* name) {
  auto it = extensions.find(name);
  return it == extensions.end() ? nullptr : &it->second;
}

double number_or(const tinygltf::Value* object, const char* key, double fallback) {
  if (!object || !object->IsObject() || !object->Has(key)) return fallback;
  const tinygltf::Value& value = object->Get(key);
  return value.IsNumber() ? value.GetNumberAsDouble() : fallback;
}

glm::vec3 rgb_or(const std::vector<double>& values, glm::vec3 fallback) {
  if (values.size() < 3) return fallback;
  return glm::vec3(float(values[0]), float(values[1]), float(values[2]));
}

glm::vec3 rgb_or(const tinygltf::Value* object, const char* key, glm::vec3 fallback) {
  if (!object || !object->IsObject() || !object->Has(key)) return fallback;
  const tinygltf::Value& v = object->Get(key);
  if (!v.IsArray() || v.ArrayLen() != 3) return fallback;
  glm::vec3 out;
  for (int i = 0; i < 3; ++i) {
    if (!v.Get(i).IsNumber()) return fallback;
    out[i] = float(v.Get(i).GetNumberAsDouble());
  }
  return out;
}

template <typename Info>
GltfTextureInfo info_of(const Info& info) {
  return {info.index, info.texCoord, find_extension(info.extensions, "KHR_texture_transform")};
}

// A textureInfo that only an extension's JSON holds (AMD_split_roughnessMetallic's).
GltfTextureInfo info_of(const tinygltf::Value* object) {
  GltfTextureInfo info;
  if (!object || !object->IsObject() || !object->Has("index") || !object->Get("index").IsInt()) return info;
  info.index = object->Get("index").GetNumberAsInt();
  if (object->Has("texCoord") && object->Get("texCoord").IsInt()) info.tex_coord = object->Get("texCoord").GetNumberAsInt();
  if (object->Has("extensions") && object->Get("extensions").Has("KHR_texture_transform"))
    info.transform = &object->Get("extensions").Get("KHR_texture_transform");
  return info;
}

// Converts materials in glTF order.
class MaterialConverter {
 public:
  MaterialConverter(const tinygltf::Model& model, GltfDiagnostics& diag, Scene& scene)
      : diag_(diag), scene_(scene), textures_(model, diag, scene) {}

  Material convert(const tinygltf::Material& source, size_t index);

 private:
  void read_glass(const tinygltf::Material& source, const std::string& name, Material& out);
  void read_metallic_roughness(const tinygltf::Material& source, const std::string& name, Material& out);
  void read_metal_maps(const tinygltf::Material& source, const std::string& name, Material& out);
  void read_specular(const tinygltf::Material& source, const std::string& name, Material& out);
  void choose_model(const tinygltf::Material& source, Material& out);
  void read_alpha_mode(const tinygltf::Material& source, Material& out);
  void read_emission(const tinygltf::Material& source, const std::string& name, Material& out);
  float least_alpha(const Material& m) const;

  GltfDiagnostics& diag_;
  Scene& scene_;
  GltfTextures textures_;
};

Material MaterialConverter::convert(const tinygltf::Material& source, size_t index) {
  const std::string name = gltf_element("materials", index);
  const tinygltf::PbrMetallicRoughness& pbr = source.pbrMetallicRoughness;
  Material out;
  out.name = source.name.empty() ? name : source.name;
  const std::vector<double>& factor = pbr.baseColorFactor;
  out.base_color = rgb_or(factor, glm::vec3(1.0f));
  out.base_alpha = factor.size() == 4 ? float(factor[3]) : 1.0f;
  out.base_color_texture = textures_.reference(info_of(pbr.baseColorTexture), name + ".baseColorTexture", true);
  if (find_extension(source.extensions, "KHR_materials_transmission") &&
      number_or(find_extension(source.extensions, "KHR_materials_transmission"), "transmissionFactor", 0.0) > 0.0)
    read_glass(source, name, out);
  else
    read_metallic_roughness(source, name, out);
  read_alpha_mode(source, out);
  out.double_sided = source.doubleSided;
  read_emission(source, name, out);
  if (source.occlusionTexture.index >= 0)
    diag_.warn_once("occlusionTexture", "occlusionTexture ignored: occlusion comes from the traced geometry");
  return out;
}

void MaterialConverter::read_glass(const tinygltf::Material& source, const std::string& name, Material& out) {
  const tinygltf::Value* transmission = find_extension(source.extensions, "KHR_materials_transmission");
  out.type = MaterialType::Glass;
  out.ior = float(number_or(find_extension(source.extensions, "KHR_materials_ior"), "ior", 1.5));
  if (number_or(transmission, "transmissionFactor", 0.0) < 1.0)
    diag_.warn_once("partial transmission", "transmissionFactor below 1 (first in " + name +
                                                ") treated as 1: the material is glass");
  if (transmission->Has("transmissionTexture"))
    diag_.warn_once("transmissionTexture", "transmissionTexture ignored: transmissionFactor is used");
}

void MaterialConverter::read_metallic_roughness(const tinygltf::Material& source, const std::string& name,
                                                Material& out) {
  const tinygltf::PbrMetallicRoughness& pbr = source.pbrMetallicRoughness;
  out.type = MaterialType::MetallicRoughness;
  out.metallic = float(std::clamp(pbr.metallicFactor, 0.0, 1.0));
  out.roughness = float(std::clamp(pbr.roughnessFactor, 0.0, 1.0));
  out.metallic_roughness_texture =
      textures_.reference(info_of(pbr.metallicRoughnessTexture), name + ".metallicRoughnessTexture", false);
  read_metal_maps(source, name, out);
  read_specular(source, name, out);
  out.normal_texture = textures_.reference(info_of(source.normalTexture), name + ".normalTexture", false);
  out.normal_scale = float(source.normalTexture.scale);
  out.alpha = std::max(out.roughness * out.roughness, kMinMetallicRoughnessAlpha);
  out.min_alpha = least_alpha(out);
  choose_model(source, out);
}

// AMD_split_roughnessMetallic: a single-channel roughness map and metal map
// in place of the core's two-channel texture, read into its channels here
// as two textures whose every channel holds the value.
void MaterialConverter::read_metal_maps(const tinygltf::Material& source, const std::string& name, Material& out) {
  const tinygltf::Value* split = find_extension(source.extensions, "AMD_split_roughnessMetallic");
  if (!split || !split->IsObject()) return;
  const std::string element = name + ".AMD_split_roughnessMetallic";
  const TextureRef roughness = textures_.reference(info_of(split->Has("roughnessTexture") ? &split->Get("roughnessTexture") : nullptr),
                                                   element + ".roughnessTexture", false);
  const TextureRef metallic = textures_.reference(info_of(split->Has("metallicTexture") ? &split->Get("metallicTexture") : nullptr),
                                                  element + ".metallicTexture", false);
  if (roughness.used()) out.roughness_texture = roughness;
  if (metallic.used()) out.metallic_texture = metallic;
}

// KHR_materials_specular and KHR_materials_ior: the coat's F0 and weight.
void MaterialConverter::read_specular(const tinygltf::Material& source, const std::string& name, Material& out) {
  const tinygltf::Value* ior = find_extension(source.extensions, "KHR_materials_ior");
  out.ior = float(number_or(ior, "ior", 1.5));
  const float f0 = (out.ior - 1.0f) / (out.ior + 1.0f);
  const tinygltf::Value* specular = find_extension(source.extensions, "KHR_materials_specular");
  const glm::vec3 colour = rgb_or(specular, "specularColorFactor", glm::vec3(1.0f));
  out.specular_f0 = glm::min(f0 * f0 * glm::max(colour, glm::vec3(0.0f)), glm::vec3(1.0f));
  out.specular_weight = float(std::clamp(number_or(specular, "specularFactor", 1.0), 0.0, 1.0));
  if (specular && (specular->Has("specularTexture") || specular->Has("specularColorTexture")))
    diag_.warn_once("specularTexture", "KHR_materials_specular's textures ignored (first in " + name +
                                           "): specularFactor and specularColorFactor are used");
}

// The fast models where the glTF BRDF reduces to one: Lambert, a mirror, or
// (extras.igi_fresnel "constant") the built-in scenes' constant-Fresnel metal.
void MaterialConverter::choose_model(const tinygltf::Material& source, Material& out) {
  const bool textured = out.metallic_roughness_texture.used() || out.metallic_texture.used() ||
                        out.roughness_texture.used() || out.normal_texture.used();
  if (textured) return;
  const bool constant_fresnel = source.extras.IsObject() && source.extras.Has("igi_fresnel") &&
                                source.extras.Get("igi_fresnel").IsString() &&
                                source.extras.Get("igi_fresnel").Get<std::string>() == "constant";
  if (out.metallic == 0.0f && out.specular_weight == 0.0f) {
    out.type = MaterialType::Diffuse;
  } else if (out.metallic == 1.0f && out.roughness == 0.0f) {
    out.type = MaterialType::Mirror;
    out.schlick_fresnel = !constant_fresnel;
  } else if (out.metallic == 1.0f && constant_fresnel) {
    out.type = MaterialType::Conductor;
    out.alpha = out.roughness * out.roughness;
  }
}

// The least alpha a surface of m can have (the glossy threshold's choices: caustics on or off).
float MaterialConverter::least_alpha(const Material& m) const {
  float roughness = m.roughness;
  auto least = [&](const TextureRef& ref, int channel) {
    const Texture& t = scene_.textures[size_t(ref.index)];
    float low = 1.0f;
    for (int y = 0; y < t.height; ++y)
      for (int x = 0; x < t.width; ++x) low = std::min(low, t.texel(x, y)[channel]);
    return low;
  };
  if (m.roughness_texture.used()) roughness *= least(m.roughness_texture, 1);
  else if (m.metallic_roughness_texture.used()) roughness *= least(m.metallic_roughness_texture, 1);
  return std::max(roughness * roughness, kMinMetallicRoughnessAlpha);
}

void MaterialConverter::read_alpha_mode(const tinygltf::Material& source, Material& out) {
  if (source.alphaMode == "MASK") {
    out.alpha_mask = true;
    out.alpha_cutoff = float(source.alphaCutoff);
  } else if (source.alphaMode == "BLEND") {
    diag_.warn_once("alphaMode BLEND", "alphaMode BLEND treated as MASK with alphaCutoff 0.5");
    out.alpha_mask = true;
    out.alpha_cutoff = 0.5f;
  } else if (source.alphaMode != "OPAQUE") {
    diag_.warn_once("alphaMode " + source.alphaMode,
                    "alphaMode '" + source.alphaMode + "' is not a glTF alpha mode: treated as OPAQUE");
  }
}

// Radiance: factor x strength, times the emissive texture's mean (lights
// emit one radiance a triangle; the pattern itself is not drawn).
void MaterialConverter::read_emission(const tinygltf::Material& source, const std::string& name, Material& out) {
  const double strength = number_or(find_extension(source.extensions, "KHR_materials_emissive_strength"),
                                    "emissiveStrength", 1.0);
  out.emission = glm::max(rgb_or(source.emissiveFactor, glm::vec3(0.0f)) * float(strength), glm::vec3(0.0f));
  if (source.emissiveTexture.index < 0 || !out.is_emissive()) return;
  const TextureRef emissive = textures_.reference(info_of(source.emissiveTexture), name + ".emissiveTexture", true);
  if (!emissive.used()) return;
  out.emission *= glm::vec3(scene_.textures[size_t(emissive.index)].mean());
  diag_.warn_once("emissiveTexture", "emissiveTexture read as its mean colour (first in " + name +
                                         "): each emitter glows evenly, with the texture's light in total");
}

}  // namespace

void convert_materials(const tinygltf::Model& model, GltfDiagnostics& diag, Scene& scene) {
  MaterialConverter converter(model, diag, scene);
  scene.materials.reserve(model.materials.size());
  for (size_t i = 0; i < model.materials.size(); ++i)
    scene.materials.push_back(converter.convert(model.materials[i], i));
}

Material default_gltf_material() {
  Material material;
  material.name = "glTF default";
  material.type = MaterialType::MetallicRoughness;
  material.base_color = glm::vec3(1.0f);
  material.metallic = 1.0f;
  material.roughness = 1.0f;
  material.alpha = 1.0f;
  material.min_alpha = 1.0f;
  material.double_sided = false;
  return material;
}

}  // namespace igi
