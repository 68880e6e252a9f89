#pragma once
// Checks on a glTF file's JSON text, made before tinygltf parses it, for what
// tinygltf would crash on or take silently:
//   nesting   tinygltf converts `extras` and `extensions` recursively, so 41 kB
//             of '[' (20,000 levels) overflow the stack. glTF itself nests a
//             few levels; more than kMaxJsonDepth is an error.
//   numbers   tinygltf reads a negative, fractional or too large byteOffset
//             or byteStride as absent (0); glTF asks for integers >= 0.
// The text is the .gltf file, or the JSON chunk of a .glb. Each check throws
// SceneError naming the file, the element and what was expected.
#include <cstdint>
#include <span>

#include "scene/gltf_diagnostics.h"

namespace igi {

inline constexpr int kMaxJsonDepth = 64;  // arrays and objects inside one another

// A scan over the bytes: brackets outside strings (escapes honoured). Call first.
void check_json_depth(std::span<const uint8_t> json, const GltfDiagnostics& diag);

// The offsets, lengths, strides and counts of accessors, bufferViews and
// buffers, where present, are integers >= 0. Text that does not parse is
// left to tinygltf, which reports it.
void check_unsigned_fields(std::span<const uint8_t> json, const GltfDiagnostics& diag);

}  // namespace igi
