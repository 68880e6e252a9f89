#include "scene/gltf_textures.h"

#include <climits>
#include <cmath>
#include <tuple>

#include <tiny_gltf.h>

#include "scene/gltf_accessors.h"
#include "scene/texture_decode.h"

namespace igi {
namespace {

// A number, or `fallback` when absent; an error when present and not a number.
double number_field(const tinygltf::Value& object, const char* key, double fallback, const std::string& element,
                    const GltfDiagnostics& diag) {
  if (!object.Has(key)) return fallback;
  const tinygltf::Value& v = object.Get(key);
  if (!v.IsNumber() || !std::isfinite(v.GetNumberAsDouble()))
    diag.fail(element + ".KHR_texture_transform." + key, "expected a finite number");
  return v.GetNumberAsDouble();
}

glm::vec2 pair_field(const tinygltf::Value& object, const char* key, glm::vec2 fallback, const std::string& element,
                     const GltfDiagnostics& diag) {
  if (!object.Has(key)) return fallback;
  const tinygltf::Value& v = object.Get(key);
  glm::vec2 out;
  for (int i = 0; i < 2; ++i) {
    if (!v.IsArray() || v.ArrayLen() != 2 || !v.Get(i).IsNumber() || !std::isfinite(v.Get(i).GetNumberAsDouble()))
      diag.fail(element + ".KHR_texture_transform." + key, "expected two finite numbers");
    out[i] = float(v.Get(i).GetNumberAsDouble());
  }
  return out;
}

}  // namespace

TextureRef GltfTextures::reference(const GltfTextureInfo& info, const std::string& element, bool srgb) {
  if (info.index < 0) return {};
  if (size_t(info.index) >= model_.textures.size())
    diag_.fail(element, "texture " + std::to_string(info.index) + " does not exist (the file has " +
                            std::to_string(model_.textures.size()) + ")");
  warn_sampler(model_.textures[size_t(info.index)].sampler);
  const int image = image_of(info.index, element);
  if (image < 0) return {};
  return transformed(info, decoded(image, srgb), element);
}

// KHR_texture_transform: u' = T R S u, R = [cos r, sin r; -sin r, cos r].
TextureRef GltfTextures::transformed(const GltfTextureInfo& info, int slot, const std::string& element) {
  TextureRef ref;
  ref.index = slot;
  int tex_coord = info.tex_coord;
  if (info.transform && info.transform->IsObject()) {
    const tinygltf::Value& t = *info.transform;
    const glm::vec2 offset = pair_field(t, "offset", glm::vec2(0.0f), element, diag_);
    const glm::vec2 scale = pair_field(t, "scale", glm::vec2(1.0f), element, diag_);
    const float rotation = float(number_field(t, "rotation", 0.0, element, diag_));
    tex_coord = int(number_field(t, "texCoord", double(tex_coord), element, diag_));
    const float c = std::cos(rotation), s = std::sin(rotation);
    ref.linear = glm::mat2(glm::vec2(c * scale.x, -s * scale.x), glm::vec2(s * scale.y, c * scale.y));
    ref.offset = offset;
    ref.transformed = true;
  }
  if (tex_coord != 0)
    diag_.warn_once("texCoord", element + " reads TEXCOORD_" + std::to_string(tex_coord) +
                                    ": TEXCOORD_0 is used (the only uv set loaded)");
  return ref;
}

int GltfTextures::image_of(int texture, const std::string& element) {
  const tinygltf::Texture& t = model_.textures[size_t(texture)];
  int image = t.source;
  if (image < 0) {  // only an extension's source: a DDS the loader may read
    const auto dds = t.extensions.find("MSFT_texture_dds");
    if (dds != t.extensions.end() && dds->second.Has("source") && dds->second.Get("source").IsInt())
      image = dds->second.Get("source").GetNumberAsInt();
  }
  if (image >= 0 && size_t(image) >= model_.images.size())
    diag_.fail(gltf_element("textures", size_t(texture)),
               "source " + std::to_string(image) + " does not exist (the file has " +
                   std::to_string(model_.images.size()) + " images)");
  if (image < 0)  // e.g. only KHR_texture_basisu's source
    diag_.warn_once("texture source " + element, gltf_element("textures", size_t(texture)) + " (" + element +
                                                     ") has no image source the loader can read: its factor is used");
  return image;
}

// Images are decoded here rather than by tinygltf, after every bufferView
// has been checked against its buffer (see parse_model in gltf_loader.cpp).
int GltfTextures::decoded(int index, bool srgb) {
  const auto cached = slot_of_image_.find({index, srgb});
  if (cached != slot_of_image_.end()) return cached->second;
  const tinygltf::Image& image = model_.images[size_t(index)];
  const std::string name = gltf_element("images", size_t(index));
  const std::string shown = image.uri.empty() ? name : name + " ('" + image.uri.substr(0, 200) + "')";
  const unsigned char* bytes = image.image.data();
  size_t size = image.image.size();
  if (image.bufferView >= 0) std::tie(bytes, size) = buffer_view_bytes(model_, image.bufferView, name, diag_);
  if (size == 0 && image.bufferView >= 0) diag_.fail(shown, "the bufferView is empty");
  if (size == 0) diag_.fail(shown, "the image file is missing, empty or outside the scene's folder");
  if (size > size_t(INT_MAX)) diag_.fail(shown, std::to_string(size) + " bytes, over the 2 GiB image limit");
  const int slot = int(scene_.textures.size());
  scene_.textures.push_back(is_dds(bytes, size) ? decode_dds_bc4(bytes, size, shown, diag_)
                                                : decode_texture(bytes, size, shown, diag_, srgb));
  slot_of_image_[{index, srgb}] = slot;
  return slot;
}

void GltfTextures::warn_sampler(int sampler) {
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

}  // namespace igi
