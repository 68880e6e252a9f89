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
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "scene/gltf_diagnostics.h"

namespace igi {

inline constexpr int kMaxJsonDepth = 64;  // arrays and objects inside one another

// A scan over the bytes: brackets outside strings (escapes honoured). Call first.
void check_json_depth(std::span<const uint8_t> json, const GltfDiagnostics& diag);

// The offsets, lengths, strides and counts of accessors, bufferViews and
// buffers, where present, are integers >= 0. Text that does not parse is
// left to tinygltf, which reports it.
void check_unsigned_fields(std::span<const uint8_t> json, const GltfDiagnostics& diag);

// --ignore-extension: the document as if the named extensions were absent:
// their entries of extensionsUsed and extensionsRequired and every
// "extensions" object's member of that name, anywhere, removed. The loader
// reads a file so, and the master sends it so, which is how workers read it
// as the master does without being told. True when something was removed.
bool strip_extensions(nlohmann::json& doc, const std::vector<std::string>& names);
// The same on a file's bytes (.gltf text, or a .glb whose JSON chunk is
// rewritten and whose other chunks are kept); nullopt when nothing names
// them (or the JSON does not parse: tinygltf says why). `removed` gets the
// names that the file did mention.
std::optional<std::vector<uint8_t>> without_extensions(std::span<const uint8_t> file, bool binary,
                                                       const std::vector<std::string>& names,
                                                       std::vector<std::string>* removed = nullptr);

}  // namespace igi
