#pragma once
// The glTF node tree flattened: every mesh instance, punctual light and the
// camera, each with its node's world transform.
//
// The tree walked is the default scene, else scene 0, else every node that
// is no other node's child. Nodes are visited depth first, parents before
// children, in file order; "the first camera" means first in that order.
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/gltf_diagnostics.h"
#include "scene/scene.h"

namespace tinygltf {
class Model;
}

namespace igi {

struct MeshInstance {
  int mesh = -1;
  glm::dmat4 world{1.0};  // object to world, column vectors
};

struct FlattenedNodes {
  std::vector<MeshInstance> instances;
  std::vector<PunctualLight> lights;  // KHR_lights_punctual, radiometric
  std::optional<Camera> camera;       // first perspective camera, if any
  std::string scene_name;             // the walked scene's name, may be empty
};

FlattenedNodes flatten_nodes(const tinygltf::Model& model, GltfDiagnostics& diag);

}  // namespace igi
