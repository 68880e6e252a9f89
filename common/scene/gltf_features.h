#pragma once
// Everything in a glTF file that the renderer does not model, reported once
// per feature with what became of it, so nothing is dropped silently:
// animations, skins, morph targets, extra scenes and every extension other
// than the four the loader reads (KHR_lights_punctual,
// KHR_materials_transmission, KHR_materials_ior,
// KHR_materials_emissive_strength).
//
// Features the mesh and material readers meet on their way (primitive modes,
// extra attributes, textures other than baseColor) are reported there.
//
// An extension in extensionsRequired that is not one of the four is an
// error: glTF asks a loader to refuse a file it cannot read as meant.
#include "scene/gltf_diagnostics.h"

namespace tinygltf {
class Model;
}

namespace igi {

// Throws SceneError naming the first required extension the loader does not read.
void check_required_extensions(const tinygltf::Model& model, const GltfDiagnostics& diag);
void warn_unsupported_features(const tinygltf::Model& model, GltfDiagnostics& diag);

}  // namespace igi
