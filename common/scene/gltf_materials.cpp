#include "scene/gltf_materials.h"

#include <algorithm>
#include <climits>
#include <cstring>
#include <cmath>
#include <map>
#include <optional>
#include <tuple>

#include <tiny_gltf.h>

#include "image/image.h"
#include "scene/gltf_accessors.h"

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

// stb decodes to 4 channels of 8 or 16 bits, row 0 at the top (as Texture).
std::string trimmed(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  return text;
}

Texture to_linear_texture(const tinygltf::Image& image) {
  Texture texture;
  texture.width = image.width;
  texture.height = image.height;
  const size_t count = size_t(image.width) * size_t(image.height);
  texture.texels.resize(count);
  const bool wide = image.bits == 16;
  const float scale = wide ? 1.0f / 65535.0f : 1.0f / 255.0f;
  for (size_t i = 0; i < count; ++i) {
    glm::vec4 encoded;
    for (int c = 0; c < 4; ++c) {
      const size_t at = i * 4 + size_t(c);
      encoded[c] = wide ? float(image.image[2 * at] | (image.image[2 * at + 1] << 8)) * scale
                        : float(image.image[at]) * scale;
    }
    texture.texels[i] = glm::vec4(srgb_to_linear(encoded.r), srgb_to_linear(encoded.g),
                                  srgb_to_linear(encoded.b), encoded.a);
  }
  return texture;
}

uint32_t big_endian(const unsigned char* at, int bytes) {
  uint32_t value = 0;
  for (int i = 0; i < bytes; ++i) value = value << 8 | at[i];
  return value;
}

// Width and height from a PNG or JPEG header, read before decoding so that a
// small file cannot make the decoder allocate gigabytes. nullopt: neither
// format (glTF allows only these two), or a header cut short.
std::optional<glm::ivec2> encoded_image_size(const unsigned char* bytes, size_t size) {
  static const unsigned char png[] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (size >= 24 && std::equal(png, png + 8, bytes) && std::memcmp(bytes + 12, "IHDR", 4) == 0)
    return glm::ivec2(int(std::min(big_endian(bytes + 16, 4), uint32_t(INT_MAX))),
                      int(std::min(big_endian(bytes + 20, 4), uint32_t(INT_MAX))));
  if (size < 4 || bytes[0] != 0xFF || bytes[1] != 0xD8) return std::nullopt;
  // JPEG: segments FF <marker> <u16 length> ... up to a start-of-frame.
  for (size_t at = 2; at + 4 <= size;) {
    if (bytes[at] != 0xFF) return std::nullopt;
    const unsigned char marker = bytes[at + 1];
    if (marker == 0xFF) { ++at; continue; }  // fill byte
    const bool start_of_frame =
        marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
    if (start_of_frame) {  // FF Cn, length, precision, height, width
      if (at + 9 > size) return std::nullopt;
      return glm::ivec2(big_endian(bytes + at + 7, 2), big_endian(bytes + at + 5, 2));
    }
    at += 2 + big_endian(bytes + at + 2, 2);
  }
  return std::nullopt;
}

// Texels are stored as float4: 2^26 of them are 1 GiB. A header may also
// claim more pixels than its file can hold: stb decodes a JPEG whose scans
// are cut short or missing as if the rest were there, so a 600-byte file
// that says 8000 x 8000 took 12 s and 1.4 GB before this check. The most
// pixels a byte can hold:
// - PNG: 8 (1-bit pixels) times deflate's largest ratio, 1032:1.
// - JPEG: a scan spends at least one bit on each 8 x 8 block (a 1-bit DC
//   code, progressive); 1024 is twice that, for slack. Real files stay far
//   below: a flat 4:2:0 JPEG with the standard tables holds about 64.
void check_image_size(const unsigned char* bytes, size_t size, const std::string& name, const GltfDiagnostics& diag) {
  constexpr int64_t kMaxTexels = int64_t(1) << 26;
  const std::optional<glm::ivec2> extent = encoded_image_size(bytes, size);
  if (!extent) diag.fail(name, "neither a PNG nor a JPEG image (or its header is cut short)");
  const int64_t texels = int64_t(extent->x) * extent->y;
  if (extent->x <= 0 || extent->y <= 0 || texels > kMaxTexels)
    diag.fail(name, std::to_string(extent->x) + " x " + std::to_string(extent->y) +
                         " pixels, expected at least 1 x 1 and at most 2^26 pixels");
  const bool png = bytes[0] == 0x89;
  const int64_t per_byte = png ? 8 * 1032 : 1024;
  if (texels > per_byte * int64_t(size))
    diag.fail(name, std::to_string(extent->x) + " x " + std::to_string(extent->y) + " pixels in " +
                         std::to_string(size) + " bytes: more than a " + (png ? "PNG" : "JPEG") +
                         " file of that size can hold (" + std::to_string(per_byte) +
                         " pixels a byte); the file is cut short or broken");
}

// Converts materials in glTF order; decodes each used image once.
class MaterialConverter {
 public:
  MaterialConverter(const tinygltf::Model& model, GltfDiagnostics& diag, Scene& scene)
      : model_(model), diag_(diag), scene_(scene) {}

  Material convert(const tinygltf::Material& source, size_t index);

 private:
  void choose_model(const tinygltf::Material& source, const std::string& name, Material& out);
  void read_alpha_mode(const tinygltf::Material& source, Material& out);
  void warn_ignored_textures(const tinygltf::Material& source);
  int base_color_texture(const tinygltf::TextureInfo& info, const std::string& name);
  void warn_sampler(int sampler);
  Texture decode_image(int image);

  const tinygltf::Model& model_;
  GltfDiagnostics& diag_;
  Scene& scene_;
  std::map<int, int> texture_of_image_;  // glTF image -> index in scene_.textures, or -1
};

Material MaterialConverter::convert(const tinygltf::Material& source, size_t index) {
  const std::string name = gltf_element("materials", index);
  const tinygltf::PbrMetallicRoughness& pbr = source.pbrMetallicRoughness;
  Material out;
  out.name = source.name.empty() ? name : source.name;
  const std::vector<double>& factor = pbr.baseColorFactor;
  out.base_color = rgb_or(factor, glm::vec3(1.0f));
  out.base_alpha = factor.size() == 4 ? float(factor[3]) : 1.0f;
  choose_model(source, name, out);
  out.base_color_texture = base_color_texture(pbr.baseColorTexture, name);
  read_alpha_mode(source, out);
  out.double_sided = source.doubleSided;

  const double strength = number_or(find_extension(source.extensions, "KHR_materials_emissive_strength"),
                                    "emissiveStrength", 1.0);
  out.emission = glm::max(rgb_or(source.emissiveFactor, glm::vec3(0.0f)) * float(strength), glm::vec3(0.0f));
  warn_ignored_textures(source);
  return out;
}

void MaterialConverter::choose_model(const tinygltf::Material& source, const std::string& name,
                                     Material& out) {
  const tinygltf::Value* transmission = find_extension(source.extensions, "KHR_materials_transmission");
  const double transmission_factor = number_or(transmission, "transmissionFactor", 0.0);
  if (transmission_factor > 0.0) {
    out.type = MaterialType::Glass;
    out.ior = float(number_or(find_extension(source.extensions, "KHR_materials_ior"), "ior", 1.5));
    if (transmission_factor < 1.0)
      diag_.warn_once("partial transmission", "transmissionFactor below 1 (first in " + name +
                                                  ") treated as 1: the material is glass");
    if (transmission->Has("transmissionTexture"))
      diag_.warn_once("transmissionTexture", "transmissionTexture ignored: transmissionFactor is used");
    return;
  }
  const double metallic = std::clamp(source.pbrMetallicRoughness.metallicFactor, 0.0, 1.0);
  const double roughness = std::clamp(source.pbrMetallicRoughness.roughnessFactor, 0.0, 1.0);
  if (metallic != 0.0 && metallic != 1.0)
    diag_.warn_once("intermediate metallic",
                    "metallicFactor between 0 and 1 (first in " + name +
                        ") rounded to the nearest: >= 0.5 is a conductor, below is diffuse");
  if (metallic < 0.5) {
    out.type = MaterialType::Diffuse;
  } else if (roughness > 0.0) {
    out.type = MaterialType::Conductor;
    out.alpha = float(roughness * roughness);
  } else {
    out.type = MaterialType::Mirror;
  }
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

void MaterialConverter::warn_ignored_textures(const tinygltf::Material& source) {
  if (source.pbrMetallicRoughness.metallicRoughnessTexture.index >= 0)
    diag_.warn_once("metallicRoughnessTexture",
                    "metallicRoughnessTexture ignored: metallicFactor and roughnessFactor are used");
  if (source.normalTexture.index >= 0)
    diag_.warn_once("normalTexture", "normalTexture ignored: shading uses interpolated vertex normals");
  if (source.occlusionTexture.index >= 0)
    diag_.warn_once("occlusionTexture", "occlusionTexture ignored: occlusion comes from the traced geometry");
  if (source.emissiveTexture.index >= 0)
    diag_.warn_once("emissiveTexture", "emissiveTexture ignored: emission is the uniform emissiveFactor");
}

int MaterialConverter::base_color_texture(const tinygltf::TextureInfo& info, const std::string& name) {
  if (info.index < 0) return -1;
  if (size_t(info.index) >= model_.textures.size())
    diag_.fail(name + ".pbrMetallicRoughness.baseColorTexture",
               "texture " + std::to_string(info.index) + " does not exist (the file has " +
                   std::to_string(model_.textures.size()) + ")");
  if (info.texCoord != 0)
    diag_.warn_once("texCoord", "baseColorTexture texCoord " + std::to_string(info.texCoord) +
                                    " ignored: TEXCOORD_0 is used");
  const tinygltf::Texture& texture = model_.textures[size_t(info.index)];
  warn_sampler(texture.sampler);
  const int image = texture.source;
  if (image >= 0 && size_t(image) >= model_.images.size())
    diag_.fail(gltf_element("textures", size_t(info.index)),
               "source " + std::to_string(image) + " does not exist (the file has " +
                   std::to_string(model_.images.size()) + " images)");
  if (image < 0) {  // e.g. only an extension's source (KHR_texture_basisu)
    diag_.warn_once("texture source",
                    gltf_element("textures", size_t(info.index)) +
                        " has no image source the loader can read: baseColorFactor is used");
    return -1;
  }
  auto cached = texture_of_image_.find(image);
  if (cached != texture_of_image_.end()) return cached->second;
  const int slot = int(scene_.textures.size());
  scene_.textures.push_back(decode_image(image));
  texture_of_image_[image] = slot;
  return slot;
}


void MaterialConverter::warn_sampler(int sampler) {
  if (sampler < 0 || size_t(sampler) >= model_.samplers.size()) return;
  const tinygltf::Sampler& s = model_.samplers[size_t(sampler)];
  if (s.wrapS != TINYGLTF_TEXTURE_WRAP_REPEAT || s.wrapT != TINYGLTF_TEXTURE_WRAP_REPEAT)
    diag_.warn_once("sampler wrap", "sampler wrap modes other than REPEAT ignored: textures repeat");
  const bool filtered = (s.minFilter != -1 && s.minFilter != TINYGLTF_TEXTURE_FILTER_LINEAR) ||
                        (s.magFilter != -1 && s.magFilter != TINYGLTF_TEXTURE_FILTER_LINEAR);
  if (filtered)
    diag_.warn_once("sampler filter",
                    "sampler filter modes ignored: textures are filtered bilinearly without mipmaps");
}

// Images are decoded here rather than by tinygltf, after every bufferView
// has been checked against its buffer (see parse_model in gltf_loader.cpp).
// A texture the file asks for and the loader cannot read is an error, not a
// silent fallback to baseColorFactor: the render would look plausible and wrong.
Texture MaterialConverter::decode_image(int index) {
  const tinygltf::Image& image = model_.images[size_t(index)];
  const std::string name = gltf_element("images", size_t(index));
  const std::string shown = image.uri.empty() ? name : name + " ('" + image.uri.substr(0, 200) + "')";
  const unsigned char* bytes = image.image.data();
  size_t size = image.image.size();
  if (image.bufferView >= 0) std::tie(bytes, size) = buffer_view_bytes(model_, image.bufferView, name, diag_);
  if (size == 0 && image.bufferView >= 0) diag_.fail(shown, "the bufferView is empty");
  if (size == 0) diag_.fail(shown, "the image file is missing, empty or outside the scene's folder");
  if (size > size_t(INT_MAX)) diag_.fail(shown, std::to_string(size) + " bytes, over the 2 GiB image limit");
  return decode_texture(bytes, size, shown, diag_);
}

}  // namespace

Texture decode_texture(const unsigned char* bytes, size_t size, const std::string& shown, const GltfDiagnostics& diag) {
  check_image_size(bytes, size, shown, diag);
  std::string error, warning;
  tinygltf::Image decoded;
  const bool ok = tinygltf::LoadImageData(&decoded, 0, &error, &warning, 0, 0, bytes, int(size), nullptr);
  const size_t expected_bytes = size_t(decoded.width) * size_t(decoded.height) * 4 * size_t(decoded.bits / 8);
  if (!ok || decoded.component != 4 || (decoded.bits != 8 && decoded.bits != 16) ||
      decoded.image.size() != expected_bytes)
    diag.fail(shown, "cannot be decoded" + (error.empty() ? std::string() : " (" + trimmed(error) + ")") +
                         ": expected a PNG or JPEG image");
  return to_linear_texture(decoded);
}

void convert_materials(const tinygltf::Model& model, GltfDiagnostics& diag, Scene& scene) {
  MaterialConverter converter(model, diag, scene);
  scene.materials.reserve(model.materials.size());
  for (size_t i = 0; i < model.materials.size(); ++i)
    scene.materials.push_back(converter.convert(model.materials[i], i));
}

Material default_gltf_material() {
  Material material;
  material.name = "glTF default";
  material.type = MaterialType::Conductor;
  material.base_color = glm::vec3(1.0f);
  material.alpha = 1.0f;
  material.double_sided = false;
  return material;
}

}  // namespace igi
