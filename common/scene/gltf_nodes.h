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

#include "scene/animation.h"
#include "scene/gltf_diagnostics.h"
#include "scene/scene.h"

namespace tinygltf {
class Model;
}

namespace igi {

struct MeshInstance {
  int mesh = -1;
  glm::dmat4 world{1.0};  // object to world, column vectors
  int pose_node = -1;     // the moving node it follows (FlattenedNodes::pose_nodes), or -1: static
};

struct FlattenedNodes {
  std::vector<MeshInstance> instances;
  std::vector<PunctualLight> lights;  // KHR_lights_punctual, radiometric
  std::optional<Camera> camera;       // first perspective camera, if any
  int camera_pose_node = -1;          // the moving node it follows (pose_nodes), or -1: static
  std::string scene_name;             // the walked scene's name, may be empty
  // The nodes that move: those `animated` marks and every node below one,
  // parents first; and which of them each light follows (-1: static).
  std::vector<PoseNode> pose_nodes;
  std::vector<int> pose_node_of;  // per glTF node: index into pose_nodes, or -1
  std::vector<int> light_pose_node;
};

// `animated` has one flag per glTF node (or is empty: nothing moves). Light
// intensities are multiplied by `light_scale` into W/sr and W/m^2 (1/683 for
// glTF's candela and lux: scene/light_units.h).
FlattenedNodes flatten_nodes(const tinygltf::Model& model, const std::vector<bool>& animated, double light_scale,
                             GltfDiagnostics& diag);

}  // namespace igi
