#include "scene/gltf_json.h"

#include <algorithm>
#include <cstring>
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

namespace {

bool named(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

bool strip_members(nlohmann::json& value, const std::vector<std::string>& names) {
  bool removed = false;
  if (value.is_object()) {
    const auto extensions = value.find("extensions");
    if (extensions != value.end() && extensions->is_object())
      for (const std::string& name : names) removed |= extensions->erase(name) > 0;
    for (auto& member : value.items()) removed |= strip_members(member.value(), names);
  } else if (value.is_array()) {
    for (nlohmann::json& element : value) removed |= strip_members(element, names);
  }
  return removed;
}

uint32_t read_u32(std::span<const uint8_t> bytes, size_t at) {
  uint32_t value;
  std::memcpy(&value, bytes.data() + at, 4);  // GLB is little-endian, as is every machine this runs on
  return value;
}

void put_u32(std::vector<uint8_t>& out, size_t at, uint32_t value) { std::memcpy(out.data() + at, &value, 4); }

}  // namespace

bool strip_extensions(nlohmann::json& doc, const std::vector<std::string>& names) {
  bool removed = false;
  for (const char* list : {"extensionsUsed", "extensionsRequired"}) {
    const auto entries = doc.find(list);
    if (entries == doc.end() || !entries->is_array()) continue;
    const auto before = entries->size();
    entries->erase(std::remove_if(entries->begin(), entries->end(),
                                  [&](const nlohmann::json& e) { return e.is_string() && named(names, e.get<std::string>()); }),
                   entries->end());
    removed |= entries->size() != before;
  }
  return strip_members(doc, names) || removed;
}

std::optional<std::vector<uint8_t>> without_extensions(std::span<const uint8_t> file, bool binary,
                                                       const std::vector<std::string>& names,
                                                       std::vector<std::string>* removed) {
  if (names.empty()) return std::nullopt;
  // A .glb: header, then the JSON chunk (length, type, text); the BIN chunk follows (check_glb read the framing).
  const size_t json_at = binary ? 20 : 0;
  const size_t json_length = binary ? std::min<size_t>(read_u32(file, 12), file.size() - 20) : file.size();
  nlohmann::json doc = nlohmann::json::parse(file.begin() + json_at, file.begin() + json_at + json_length, nullptr, false);
  if (!doc.is_object()) return std::nullopt;
  bool any = false;
  for (const std::string& name : names)
    if (strip_extensions(doc, {name})) {
      any = true;
      if (removed) removed->push_back(name);
    }
  if (!any) return std::nullopt;
  std::string text = doc.dump();
  if (!binary) return std::vector<uint8_t>(text.begin(), text.end());
  text.resize((text.size() + 3) & ~size_t(3), ' ');
  std::vector<uint8_t> out(file.begin(), file.begin() + 20);
  out.insert(out.end(), text.begin(), text.end());
  out.insert(out.end(), file.begin() + json_at + json_length, file.end());
  put_u32(out, 8, uint32_t(out.size()));
  put_u32(out, 12, uint32_t(text.size()));
  return out;
}

}  // namespace igi
