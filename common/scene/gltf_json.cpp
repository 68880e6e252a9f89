#include "scene/gltf_json.h"

#include <initializer_list>
#include <string>

#include <nlohmann/json.hpp>

namespace igi {
namespace {

// Each named field of each element of doc[array] that is present must be an
// integer >= 0 (nlohmann keeps those, and only those, as unsigned).
void check_fields(const nlohmann::json& doc, const char* array, std::initializer_list<const char*> fields,
                  const GltfDiagnostics& diag) {
  const auto elements = doc.find(array);
  if (elements == doc.end() || !elements->is_array()) return;
  for (size_t i = 0; i < elements->size(); ++i) {
    const nlohmann::json& element = (*elements)[i];
    if (!element.is_object()) continue;
    for (const char* field : fields) {
      const auto value = element.find(field);
      if (value != element.end() && !value->is_number_unsigned())
        diag.fail(gltf_element(array, i), std::string(field) + " " + value->dump() + ", expected an integer >= 0");
    }
  }
}

}  // namespace

void check_json_depth(std::span<const uint8_t> json, const GltfDiagnostics& diag) {
  int depth = 0;
  bool in_string = false, escaped = false;
  for (size_t i = 0; i < json.size(); ++i) {
    const uint8_t c = json[i];
    if (in_string) {
      if (escaped) escaped = false;
      else if (c == '\\') escaped = true;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonDepth)
        diag.fail("JSON", "arrays and objects nested deeper than " + std::to_string(kMaxJsonDepth) +
                              " levels (at byte " + std::to_string(i) + "), expected a glTF document's few");
    } else if (c == ']' || c == '}') {
      --depth;  // unbalanced brackets are tinygltf's parse error
    }
  }
}

void check_unsigned_fields(std::span<const uint8_t> json, const GltfDiagnostics& diag) {
  const nlohmann::json doc = nlohmann::json::parse(json.begin(), json.end(), nullptr, false);
  if (!doc.is_object()) return;  // discarded (not JSON) or not a document: tinygltf says why
  check_fields(doc, "accessors", {"bufferView", "byteOffset", "count"}, diag);
  check_fields(doc, "bufferViews", {"buffer", "byteOffset", "byteLength", "byteStride"}, diag);
  check_fields(doc, "buffers", {"byteLength"}, diag);
}

}  // namespace igi
