#pragma once
// A glTF document built in a test: JSON with nlohmann::json, its one binary
// buffer packed by hand, written as .gltf (with a .bin beside it) or .glb.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace igi::test {

inline void write_bytes(const std::filesystem::path& path, const std::vector<unsigned char>& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

inline constexpr int kFloat = 5126, kUnsignedInt = 5125;

// Builds a glTF document and its single binary buffer.
class GltfFile {
 public:
  GltfFile() {
    doc["asset"] = {{"version", "2.0"}};
    doc["scenes"] = nlohmann::json::array({{{"nodes", nlohmann::json::array()}}});
    doc["scene"] = 0;
  }

  int add(const char* array, nlohmann::json value) {
    doc[array].push_back(std::move(value));
    return int(doc[array].size()) - 1;
  }

  int add_view(const void* data, size_t bytes) {
    bin.resize((bin.size() + 3) / 4 * 4, 0);
    const size_t offset = bin.size();
    const auto* first = static_cast<const unsigned char*>(data);
    bin.insert(bin.end(), first, first + bytes);
    return add("bufferViews", {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}});
  }

  int add_floats(const std::vector<float>& values, const std::string& type) {
    const size_t components = type == "VEC3" ? 3 : type == "VEC2" ? 2 : 1;
    const int view = add_view(values.data(), values.size() * sizeof(float));
    return add("accessors", {{"bufferView", view}, {"componentType", kFloat},
                             {"count", values.size() / components}, {"type", type}});
  }

  int add_indices(const std::vector<uint32_t>& indices) {
    const int view = add_view(indices.data(), indices.size() * sizeof(uint32_t));
    return add("accessors", {{"bufferView", view}, {"componentType", kUnsignedInt},
                             {"count", indices.size()}, {"type", "SCALAR"}});
  }

  // Unit quad in the z = 0 plane facing +z; accessors POSITION, NORMAL,
  // TEXCOORD_0, indices are added in that order.
  int add_quad_mesh(int material = -1, std::vector<uint32_t> indices = {0, 1, 2, 0, 2, 3}) {
    nlohmann::json primitive = {{"attributes",
                       {{"POSITION", add_floats({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, "VEC3")},
                        {"NORMAL", add_floats({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3")},
                        {"TEXCOORD_0", add_floats({0, 0, 1, 0, 1, 1, 0, 1}, "VEC2")}}},
                      {"indices", add_indices(indices)}};
    if (material >= 0) primitive["material"] = material;
    return add("meshes", {{"primitives", nlohmann::json::array({primitive})}});
  }

  int add_root(nlohmann::json node) {
    const int index = add("nodes", std::move(node));
    doc["scenes"][0]["nodes"].push_back(index);
    return index;
  }

  int add_light(nlohmann::json light) {
    doc["extensionsUsed"].push_back("KHR_lights_punctual");
    nlohmann::json& lights = doc["extensions"]["KHR_lights_punctual"]["lights"];
    lights.push_back(std::move(light));
    return int(lights.size()) - 1;
  }

  std::filesystem::path write_gltf(const std::filesystem::path& dir, const std::string& stem) {
    if (!bin.empty()) doc["buffers"] = nlohmann::json::array({{{"byteLength", bin.size()}, {"uri", stem + ".bin"}}});
    const std::filesystem::path path = dir / (stem + ".gltf");
    std::ofstream(path) << doc.dump(2);
    if (!bin.empty()) write_bytes(dir / (stem + ".bin"), bin);
    return path;
  }

  // `to_text` writes the JSON chunk (tests that need text nlohmann::json cannot make).
  std::filesystem::path write_glb(const std::filesystem::path& dir, const std::string& stem,
                     const std::function<std::string(const nlohmann::json&)>& to_text = [](const nlohmann::json& d) { return d.dump(); }) {
    doc["buffers"] = nlohmann::json::array({{{"byteLength", bin.size()}}});
    std::string text = to_text(doc);
    text.resize((text.size() + 3) / 4 * 4, ' ');
    std::vector<unsigned char> chunk = bin;
    chunk.resize((chunk.size() + 3) / 4 * 4, 0);
    std::vector<unsigned char> out;
    auto u32 = [&out](uint32_t v) { for (int i = 0; i < 4; ++i) out.push_back((v >> (8 * i)) & 0xff); };
    u32(0x46546C67), u32(2), u32(uint32_t(12 + 8 + text.size() + 8 + chunk.size()));
    u32(uint32_t(text.size())), u32(0x4E4F534A);
    out.insert(out.end(), text.begin(), text.end());
    u32(uint32_t(chunk.size())), u32(0x004E4942);
    out.insert(out.end(), chunk.begin(), chunk.end());
    const std::filesystem::path path = dir / (stem + ".glb");
    write_bytes(path, out);
    return path;
  }

  nlohmann::json doc;
  std::vector<unsigned char> bin;
};

}  // namespace igi::test
