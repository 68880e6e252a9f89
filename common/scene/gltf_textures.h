#pragma once
// glTF texture references as the scene's TextureRefs: which image a texture
// reads, decoded once per image and colour space (colour maps from sRGB,
// data maps linearly), and KHR_texture_transform's map of the uv.
//
// A texture reads its core `source` (PNG or JPEG); a texture without one
// reads its MSFT_texture_dds `source` where that is a DDS of BC4 blocks (the
// single-channel maps of AMD_split_roughnessMetallic); anything else (only
// KHR_texture_basisu's source, a DDS of another format) leaves the reference
// unused with one warning, and the material's factor stands alone. A texture
// the file asks for whose image is missing, broken or too large is an error
// (scene/texture_decode.h): the render would look plausible and wrong.
#include <map>
#include <string>
#include <utility>

#include "scene/gltf_diagnostics.h"
#include "scene/scene.h"

namespace tinygltf {
class Model;
class Value;
}

namespace igi {

// The parts of a glTF textureInfo a reference needs.
struct GltfTextureInfo {
  int index = -1;
  int tex_coord = 0;
  const tinygltf::Value* transform = nullptr;  // KHR_texture_transform, when present
};

class GltfTextures {
 public:
  GltfTextures(const tinygltf::Model& model, GltfDiagnostics& diag, Scene& scene)
      : model_(model), diag_(diag), scene_(scene) {}

  // The reference `element` (for messages: "materials[2].normalTexture")
  // makes; `srgb` for colour maps. Unused when info.index < 0 or its image
  // cannot be read (warned once).
  TextureRef reference(const GltfTextureInfo& info, const std::string& element, bool srgb);

 private:
  int image_of(int texture, const std::string& element);  // -1: none the loader reads
  int decoded(int image, bool srgb);
  void warn_sampler(int sampler);
  TextureRef transformed(const GltfTextureInfo& info, int slot, const std::string& element);

  const tinygltf::Model& model_;
  GltfDiagnostics& diag_;
  Scene& scene_;
  std::map<std::pair<int, bool>, int> slot_of_image_;  // (glTF image, sRGB) -> index in scene_.textures
};

}  // namespace igi
