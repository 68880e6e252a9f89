#pragma once
// glTF materials mapped onto the renderer's four material models.
//
//   KHR_materials_transmission > 0      -> Glass, ior from KHR_materials_ior (1.5)
//   metallic >= 0.5, roughness > 0      -> Conductor, alpha = roughness^2
//   metallic >= 0.5, roughness == 0     -> Mirror
//   metallic <  0.5                     -> Diffuse, albedo = baseColor
// Emission is emissiveFactor * KHR_materials_emissive_strength, read as
// radiance. Base colour textures are decoded from sRGB to linear on load;
// alpha stays linear. A used texture whose image is missing, is not a PNG or
// JPEG, does not decode or exceeds 2^26 pixels is an error (SceneError).
// Everything else a glTF material can say is reported once through
// GltfDiagnostics and left out.
#include "scene/gltf_diagnostics.h"
#include "scene/scene.h"

namespace tinygltf {
class Model;
}

namespace igi {

// Fills scene.materials (one per glTF material, same order) and
// scene.textures (one per decoded image that a material uses).
void convert_materials(const tinygltf::Model& model, GltfDiagnostics& diag, Scene& scene);

// A PNG or JPEG file's bytes as a linear texture (sRGB decoded; alpha kept),
// after the same checks as a glTF image: its header's size at most 2^26
// pixels and no more than its bytes can hold. Throws SceneError naming `shown`.
Texture decode_texture(const unsigned char* bytes, size_t size, const std::string& shown, const GltfDiagnostics& diag);

// The material glTF prescribes for a primitive without one: white,
// metallic 1, roughness 1, single-sided; here a Conductor with alpha 1.
Material default_gltf_material();

}  // namespace igi
