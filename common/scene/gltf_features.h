#pragma once
// Everything in a glTF file that the renderer does not model, reported once
// per feature with what became of it, so nothing is dropped silently:
// animations, skins, morph targets, extra scenes and every extension other
// than those the loader reads (kReadExtensions).
//
// Features the mesh and material readers meet on their way (primitive modes,
// extra attributes, occlusion textures) are reported there.
//
// An extension in extensionsRequired that the loader does not read is an
// error: glTF asks a loader to refuse a file it cannot read as meant. The
// error names the option that loads it anyway, --ignore-extension NAME, and
// what is then lost (the loader reads the file as if the extension were
// absent: gltf_json.h strip_extensions).
#include <string>

#include "scene/gltf_diagnostics.h"

namespace tinygltf {
class Model;
}

namespace igi {

// What is lost when the loader reads a file without `extension`, for messages.
std::string extension_loss(const std::string& extension);

// Throws SceneError naming the first required extension the loader does not read.
void check_required_extensions(const tinygltf::Model& model, const GltfDiagnostics& diag);
void warn_unsupported_features(const tinygltf::Model& model, GltfDiagnostics& diag);

}  // namespace igi
