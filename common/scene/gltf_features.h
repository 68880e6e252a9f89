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
#include "scene/gltf_diagnostics.h"

namespace tinygltf {
class Model;
}

namespace igi {

void warn_unsupported_features(const tinygltf::Model& model, GltfDiagnostics& diag);

}  // namespace igi
