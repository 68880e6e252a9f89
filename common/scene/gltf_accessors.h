#pragma once
// Bounds-checked reads of glTF accessors into the renderer's vector types.
//
// tinygltf sizes every buffer from the bytes it actually read, so checking an
// accessor against its bufferView and the bufferView against its buffer ties
// every count to the file's size. All checks run before a vector is
// allocated: an accessor claiming 2^30 elements in a 1 kB file fails with a
// SceneError instead of allocating gigabytes.
//
// `role` says what the accessor is for, for messages, e.g.
// "POSITION of meshes[0].primitives[1]".
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "scene/gltf_diagnostics.h"

namespace tinygltf {
class Model;
}

namespace igi {

// Every bufferView must name an existing buffer and lie inside it. Call once,
// before any accessor or image is read.
void check_buffer_views(const tinygltf::Model& model, const GltfDiagnostics& diag);

// The bytes of a bufferView already checked by check_buffer_views.
std::pair<const unsigned char*, size_t> buffer_view_bytes(const tinygltf::Model& model, int view,
                                                          const std::string& role,
                                                          const GltfDiagnostics& diag);

// VEC3 of FLOAT (POSITION, NORMAL). With require_finite, a NaN or infinite
// component is an error naming the element.
std::vector<glm::vec3> read_vec3_floats(const tinygltf::Model& model, int accessor,
                                        const std::string& role, bool require_finite,
                                        const GltfDiagnostics& diag);

// SCALAR (components 1), VEC3 (3) or VEC4 (4) of FLOAT, every component
// finite, flattened: element i's components start at i * components.
std::vector<float> read_float_elements(const tinygltf::Model& model, int accessor, int components,
                                       const std::string& role, const GltfDiagnostics& diag);

// VEC2 of FLOAT, or of normalized UNSIGNED_BYTE / UNSIGNED_SHORT (TEXCOORD_n).
// Non-finite coordinates become (0, 0) with a warning.
std::vector<glm::vec2> read_texcoords(const tinygltf::Model& model, int accessor,
                                      const std::string& role, GltfDiagnostics& diag);

// SCALAR of UNSIGNED_BYTE / SHORT / INT; every index must be < vertex_count.
std::vector<uint32_t> read_indices(const tinygltf::Model& model, int accessor,
                                   const std::string& role, size_t vertex_count,
                                   const GltfDiagnostics& diag);

}  // namespace igi
