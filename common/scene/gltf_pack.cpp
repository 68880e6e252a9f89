#include "scene/gltf_pack.h"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <optional>
#include <set>

#include <nlohmann/json.hpp>

#include "io/file_bytes.h"
#include "scene/gltf_json.h"
#include "scene/obj_loader.h"
#include "scene/scene.h"

namespace igi {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

constexpr uint32_t kGlbMagic = 0x46546C67, kChunkJson = 0x4E4F534A, kChunkBin = 0x004E4942;

bool is_external(const json& element) {
  const auto uri = element.find("uri");
  return uri != element.end() && uri->is_string() && uri->get<std::string>().rfind("data:", 0) != 0;
}

// A URI's %XX escapes, as tinygltf decodes them.
std::string decoded_uri(const std::string& uri) {
  std::string out;
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(uint8_t(uri[i + 1])) && std::isxdigit(uint8_t(uri[i + 2]))) {
      out += char(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return out;
}

// The file a URI names, inside the scene's folder only (as the loader reads it).
std::vector<uint8_t> read_beside(const fs::path& folder, const std::string& uri, const std::string& scene) {
  std::error_code error;
  const fs::path root = fs::weakly_canonical(folder, error);
  const fs::path target = fs::weakly_canonical(folder / decoded_uri(uri), error);
  const auto [root_end, unused] = std::mismatch(root.begin(), root.end(), target.begin(), target.end());
  std::optional<std::vector<uint8_t>> bytes;
  if (!error && root_end == root.end()) bytes = read_file_bytes(target.string());
  if (!bytes) throw SceneError(scene + ": cannot read '" + uri + "' (in the scene's folder) to send it to workers");
  return *bytes;
}

// Appends `bytes` at an offset aligned to 8 (every component type's alignment), and returns the offset.
size_t append_aligned(std::vector<uint8_t>& bin, const std::vector<uint8_t>& bytes) {
  bin.resize((bin.size() + 7) & ~size_t(7), 0);
  const size_t at = bin.size();
  bin.insert(bin.end(), bytes.begin(), bytes.end());
  return at;
}

std::string image_mime_type(const std::vector<uint8_t>& bytes) {
  if (bytes.size() >= 4 && bytes[0] == 0x89 && bytes[1] == 'P' && bytes[2] == 'N' && bytes[3] == 'G') return "image/png";
  if (bytes.size() >= 2 && bytes[0] == 0xFF && bytes[1] == 0xD8) return "image/jpeg";
  return "application/octet-stream";  // the loader names what it is not
}

// Buffer 0 becomes the BIN chunk holding every external buffer; buffers with
// data: URIs stay, renumbered after it.
void pack_buffers(json& doc, std::vector<uint8_t>& bin, const fs::path& folder, const std::string& scene) {
  json& buffers = doc["buffers"];
  std::vector<int64_t> new_index(buffers.size()), offset(buffers.size(), 0);
  json kept = json::array({json::object()});
  for (size_t i = 0; i < buffers.size(); ++i) {
    if (is_external(buffers[i])) {
      new_index[i] = 0;
      offset[i] = int64_t(append_aligned(bin, read_beside(folder, buffers[i]["uri"], scene)));
    } else {
      new_index[i] = int64_t(kept.size());
      kept.push_back(buffers[i]);
    }
  }
  if (doc.contains("bufferViews") && doc["bufferViews"].is_array())
    for (json& view : doc["bufferViews"]) {
      if (!view.contains("buffer") || !view["buffer"].is_number_unsigned()) continue;  // the loader's error
      const size_t b = view["buffer"].get<size_t>();
      if (b >= new_index.size()) continue;
      view["buffer"] = new_index[b];
      if (offset[b] != 0) view["byteOffset"] = view.value("byteOffset", int64_t(0)) + offset[b];
    }
  buffers = std::move(kept);
}

// Every texture index a material names (its textureInfo objects, the
// extensions' too), but the occlusion texture, which nothing reads.
void material_textures(const json& value, std::set<int64_t>& out) {
  if (value.is_object()) {
    const auto index = value.find("index");
    if (index != value.end() && index->is_number_integer()) out.insert(index->get<int64_t>());
    for (const auto& member : value.items())
      if (member.key() != "occlusionTexture") material_textures(member.value(), out);
  } else if (value.is_array()) {
    for (const json& element : value) material_textures(element, out);
  }
}

// The images those textures read: their source, or where they have none the
// DDS that MSFT_texture_dds names (as scene/gltf_textures.h reads them).
std::set<int64_t> used_images(const json& doc) {
  std::set<int64_t> textures, images;
  if (doc.contains("materials")) material_textures(doc["materials"], textures);
  if (!doc.contains("textures") || !doc["textures"].is_array()) return images;
  for (int64_t t : textures) {
    if (t < 0 || size_t(t) >= doc["textures"].size() || !doc["textures"][size_t(t)].is_object()) continue;
    const json& texture = doc["textures"][size_t(t)];
    if (texture.contains("source") && texture["source"].is_number_integer()) {
      images.insert(texture["source"].get<int64_t>());
      continue;
    }
    const json* dds = texture.contains("extensions") ? &texture["extensions"] : nullptr;
    if (dds && dds->contains("MSFT_texture_dds") && (*dds)["MSFT_texture_dds"].contains("source") &&
        (*dds)["MSFT_texture_dds"]["source"].is_number_integer())
      images.insert((*dds)["MSFT_texture_dds"]["source"].get<int64_t>());
  }
  return images;
}

// External images some material reads become bufferViews of the BIN chunk;
// the others a placeholder (one byte, never decoded: the loader reads only
// the images materials use).
void pack_images(json& doc, std::vector<uint8_t>& bin, const fs::path& folder, const std::string& scene) {
  if (!doc.contains("images") || !doc["images"].is_array()) return;
  const std::set<int64_t> used = used_images(doc);
  int64_t placeholder = -1;
  for (size_t i = 0; i < doc["images"].size(); ++i) {
    json& image = doc["images"][i];
    if (!is_external(image)) continue;
    if (!used.count(int64_t(i))) {
      if (placeholder < 0) {
        const size_t at = append_aligned(bin, {0});
        doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", at}, {"byteLength", 1}});
        placeholder = int64_t(doc["bufferViews"].size() - 1);
      }
      image.erase("uri");
      image["bufferView"] = placeholder;
      image["mimeType"] = "image/png";
      continue;
    }
    const std::vector<uint8_t> bytes = read_beside(folder, image["uri"], scene);
    const size_t at = append_aligned(bin, bytes);
    doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", at}, {"byteLength", bytes.size()}});
    image.erase("uri");
    image["bufferView"] = doc["bufferViews"].size() - 1;
    if (!image.contains("mimeType")) image["mimeType"] = image_mime_type(bytes);
  }
}

void put_u32(std::vector<uint8_t>& out, uint32_t v) {
  const size_t at = out.size();
  out.resize(at + 4);
  std::memcpy(out.data() + at, &v, 4);  // GLB is little-endian, as is every machine this runs on
}

std::vector<uint8_t> glb(const json& doc, std::vector<uint8_t> bin) {
  std::string text = doc.dump();
  text.resize((text.size() + 3) & ~size_t(3), ' ');
  bin.resize((bin.size() + 3) & ~size_t(3), 0);
  std::vector<uint8_t> out;
  out.reserve(28 + text.size() + bin.size());
  put_u32(out, kGlbMagic);
  put_u32(out, 2);
  put_u32(out, uint32_t(12 + 8 + text.size() + 8 + bin.size()));
  put_u32(out, uint32_t(text.size()));
  put_u32(out, kChunkJson);
  out.insert(out.end(), text.begin(), text.end());
  put_u32(out, uint32_t(bin.size()));
  put_u32(out, kChunkBin);
  out.insert(out.end(), bin.begin(), bin.end());
  return out;
}

bool has_external(const json& doc, const char* array) {
  if (!doc.contains(array) || !doc[array].is_array()) return false;
  for (const json& element : doc[array])
    if (element.is_object() && is_external(element)) return true;
  return false;
}

}  // namespace

SceneFile scene_file_for_workers(const std::string& path, const std::vector<std::string>& ignored_extensions) {
  if (is_obj_file(path)) return {fs::path(path).stem().string() + ".glb", obj_as_glb(path), true};
  std::optional<std::vector<uint8_t>> bytes = read_file_bytes(path);
  if (!bytes) throw SceneError(path + ": cannot read the scene file");
  SceneFile file{fs::path(path).filename().string(), std::move(*bytes), false};
  if (file.bytes.size() >= 20 && std::memcmp(file.bytes.data(), &kGlbMagic, 4) == 0) {  // a .glb: whole
    if (auto stripped = without_extensions(file.bytes, true, ignored_extensions)) file.bytes = std::move(*stripped);
    return file;
  }
  json doc = json::parse(file.bytes.begin(), file.bytes.end(), nullptr, false);
  if (!doc.is_object()) return file;  // the loader's error
  if (strip_extensions(doc, ignored_extensions) && !(has_external(doc, "buffers") || has_external(doc, "images"))) {
    const std::string text = doc.dump();
    file.bytes.assign(text.begin(), text.end());
    return file;
  }
  if (!(has_external(doc, "buffers") || has_external(doc, "images"))) return file;
  const fs::path folder = fs::path(path).parent_path().empty() ? fs::path(".") : fs::path(path).parent_path();
  std::vector<uint8_t> bin;
  if (doc.contains("buffers") && doc["buffers"].is_array()) pack_buffers(doc, bin, folder, path);
  pack_images(doc, bin, folder, path);
  if (bin.size() > UINT32_MAX - 64) throw SceneError(path + ": its buffers and images exceed a .glb's 4 GiB");
  doc["buffers"][0]["byteLength"] = bin.size();
  file.bytes = glb(doc, std::move(bin));
  file.name = fs::path(path).stem().string() + ".glb";
  file.packed = true;
  return file;
}

}  // namespace igi
