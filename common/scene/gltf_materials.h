#pragma once
// glTF materials mapped onto the renderer's material models:
//
//   KHR_materials_transmission > 0      -> Glass, ior from KHR_materials_ior (1.5)
//   metallic 0, specularFactor 0        -> Diffuse (Lambert exactly), albedo = baseColor
//   metallic 1, roughness 0             -> Mirror with glTF's Schlick Fresnel, F0 = baseColor
//   anything else                       -> MetallicRoughness: glTF's BRDF itself
//                                          (material/metallic_roughness.h), fractional
//                                          metallic included
// (the first three only without metallic-roughness and normal textures).
// `extras: {"igi_fresnel": "constant"}` on a metallic-1 material reads it as
// the Conductor (or Mirror) of constant Fresnel = baseColor that
// --export-gltf writes for the built-in scenes' metal, so they come back as
// they were. Textures: baseColorTexture and emissiveTexture decoded from
// sRGB, metallicRoughnessTexture (blue metallic, green roughness) and
// normalTexture (with its scale; tangents from the uv layout, scene/surface.h)
// linearly, each with KHR_texture_transform; AMD_split_roughnessMetallic's
// separate single-channel maps where their images can be read. Emission is
// emissiveFactor x KHR_materials_emissive_strength x the mean of
// emissiveTexture (per material: lights need one radiance a triangle), read
// as radiance. KHR_materials_specular's specularFactor and specularColorFactor
// set the coat's Fresnel. Everything else a glTF material can say
// (occlusionTexture, the specular extension's textures, ...) is reported
// once through GltfDiagnostics and left out.
#include "scene/gltf_diagnostics.h"
#include "scene/scene.h"

namespace tinygltf {
class Model;
}

namespace igi {

// Fills scene.materials (one per glTF material, same order) and
// scene.textures (one per decoded image and colour space that a material uses).
void convert_materials(const tinygltf::Model& model, GltfDiagnostics& diag, Scene& scene);

// The material glTF prescribes for a primitive without one: white,
// metallic 1, roughness 1, single-sided.
Material default_gltf_material();

}  // namespace igi
