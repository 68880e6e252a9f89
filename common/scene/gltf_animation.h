#pragma once
// glTF animations read into channels on node translation, rotation and scale
// (LINEAR, STEP and CUBICSPLINE samplers), every count, key time and value
// checked: mismatched counts, key times that do not increase, non-finite keys
// and targets that do not exist are errors naming the file and the element.
// Morph-target weights are reported once and left out.
#include <vector>

#include "scene/animation.h"
#include "scene/gltf_diagnostics.h"

namespace tinygltf {
class Model;
}

namespace igi {

// Every channel of every animation; AnimationChannel::node holds the glTF
// node index (flatten_nodes maps it to the moving nodes it finds).
std::vector<AnimationChannel> read_gltf_animations(const tinygltf::Model& model, GltfDiagnostics& diag);

}  // namespace igi
