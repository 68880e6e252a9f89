#pragma once
// glTF triangle primitives flattened into the Scene's world-space arrays.
//
// Each primitive is read and checked once, however many nodes instance its
// mesh, then transformed per instance: positions by the node's world
// matrix, normals by its inverse transpose, and the winding flipped where
// the matrix mirrors (negative determinant) so the front face stays on the
// side the normals point to.
//
// Scene holds normals and uvs for all vertices or for none. When some
// instanced primitives have normals and others not, the latter get flat
// normals (their triangles are unwelded); missing uvs become (0, 0).
// Zero-area triangles are dropped and non-finite normals are replaced by the
// geometric normal, each with one warning that counts them.
#include <vector>

#include "scene/animation.h"
#include "scene/gltf_diagnostics.h"
#include "scene/gltf_nodes.h"
#include "scene/scene.h"

namespace tinygltf {
class Model;
}

namespace igi {

// Appends every instance's triangles to scene. scene.materials must already
// hold the file's materials; the glTF default material is appended if a
// primitive has none. Returns a part per primitive of each moving instance
// (MeshInstance::pose_node), for posing (scene/animation.h).
std::vector<DynamicPart> add_mesh_instances(const tinygltf::Model& model, const std::vector<MeshInstance>& instances,
                        GltfDiagnostics& diag, Scene& scene);

}  // namespace igi
