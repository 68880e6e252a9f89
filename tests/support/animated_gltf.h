#pragma once
// A small animated glTF for the dynamic-scene tests and the fuzzers' seeds:
// a floor and an emissive ceiling quad (static), a cube node "mover" that
// translates (LINEAR) and turns (CUBICSPLINE), a smaller cube child that
// scales (STEP), a point lamp riding on the mover, and a camera (which can
// fly too). All data in one embedded buffer. posed_copy() writes the same scene with the animation
// replaced by the nodes' translation, rotation and scale at a time, as a
// static file (nlohmann writes doubles that read back exactly).
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "scene/animation.h"

namespace igi::test {

inline std::string base64(const std::vector<uint8_t>& bytes) {
  static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const uint32_t n = uint32_t(bytes[i]) << 16 | (i + 1 < bytes.size() ? uint32_t(bytes[i + 1]) << 8 : 0) |
                       (i + 2 < bytes.size() ? uint32_t(bytes[i + 2]) : 0);
    out += digits[n >> 18 & 63];
    out += digits[n >> 12 & 63];
    out += i + 1 < bytes.size() ? digits[n >> 6 & 63] : '=';
    out += i + 2 < bytes.size() ? digits[n & 63] : '=';
  }
  return out;
}

class GltfBuilder {
 public:
  // An accessor of floats (components 1, 3 or 4) in the one buffer.
  int floats(const std::vector<float>& values, int components) {
    const size_t offset = bytes_.size();
    bytes_.resize(offset + 4 * values.size());
    std::memcpy(bytes_.data() + offset, values.data(), 4 * values.size());
    views_.push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", 4 * values.size()}});
    const char* type = components == 1 ? "SCALAR" : components == 3 ? "VEC3" : "VEC4";
    nlohmann::json accessor = {{"bufferView", views_.size() - 1}, {"componentType", 5126},
                               {"count", values.size() / size_t(components)}, {"type", type}};
    if (components == 3) {
      glm::vec3 lo(1e30f), hi(-1e30f);
      for (size_t i = 0; i < values.size(); i += 3)
        for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], values[i + k]), hi[k] = std::max(hi[k], values[i + k]);
      accessor["min"] = {lo.x, lo.y, lo.z};
      accessor["max"] = {hi.x, hi.y, hi.z};
    }
    accessors_.push_back(accessor);
    return int(accessors_.size()) - 1;
  }
  int indices(const std::vector<uint32_t>& values) {
    const size_t offset = bytes_.size();
    bytes_.resize(offset + 4 * values.size());
    std::memcpy(bytes_.data() + offset, values.data(), 4 * values.size());
    views_.push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", 4 * values.size()}});
    accessors_.push_back({{"bufferView", views_.size() - 1}, {"componentType", 5125}, {"count", values.size()},
                          {"type", "SCALAR"}});
    return int(accessors_.size()) - 1;
  }
  void finish(nlohmann::json& doc) const {
    doc["buffers"] = {{{"byteLength", bytes_.size()},
                       {"uri", "data:application/octet-stream;base64," + base64(bytes_)}}};
    doc["bufferViews"] = views_;
    doc["accessors"] = accessors_;
  }

 private:
  std::vector<uint8_t> bytes_;
  nlohmann::json views_ = nlohmann::json::array(), accessors_ = nlohmann::json::array();
};

// A unit cube centred on the origin, 24 vertices with face normals.
inline nlohmann::json cube_primitive(GltfBuilder& b, int material) {
  std::vector<float> p, n;
  std::vector<uint32_t> idx;
  for (int axis = 0; axis < 3; ++axis)
    for (int side = -1; side <= 1; side += 2) {
      const uint32_t base = uint32_t(p.size() / 3);
      glm::vec3 normal(0.0f);
      normal[axis] = float(side);
      const glm::vec3 u = glm::vec3(axis == 1, axis == 2, axis == 0), v = glm::cross(normal, u);
      for (int c = 0; c < 4; ++c) {
        const glm::vec3 q = 0.5f * (normal + float(c == 1 || c == 2 ? 1 : -1) * u + float(c >= 2 ? 1 : -1) * v);
        p.insert(p.end(), {q.x, q.y, q.z});
        n.insert(n.end(), {normal.x, normal.y, normal.z});
      }
      idx.insert(idx.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    }
  const int position = b.floats(p, 3), normal = b.floats(n, 3), indices = b.indices(idx);
  return {{"attributes", {{"POSITION", position}, {"NORMAL", normal}}}, {"indices", indices}, {"material", material}};
}

inline nlohmann::json quad_primitive(GltfBuilder& b, float y, float half, bool down, int material) {
  std::vector<float> p = {-half, y, -half, half, y, -half, half, y, half, -half, y, half};
  std::vector<uint32_t> idx = down ? std::vector<uint32_t>{0, 1, 2, 0, 2, 3} : std::vector<uint32_t>{0, 2, 1, 0, 3, 2};
  const int position = b.floats(p, 3), indices = b.indices(idx);
  return {{"attributes", {{"POSITION", position}}}, {"indices", indices}, {"material", material}};
}

// With camera_moves, the camera node flies too (translation and rotation,
// LINEAR): a camera that follows the animation.
inline nlohmann::json animated_document(bool camera_moves = false) {
  GltfBuilder b;
  nlohmann::json doc;
  doc["asset"] = {{"version", "2.0"}};
  doc["extensionsUsed"] = {"KHR_lights_punctual"};
  doc["extensions"]["KHR_lights_punctual"]["lights"] = {{{"type", "point"}, {"intensity", 2.0 * 683}, {"color", {1, 0.9, 0.8}}}};
  doc["materials"] = {{{"name", "grey"}, {"pbrMetallicRoughness", {{"baseColorFactor", {0.7, 0.7, 0.7, 1}}, {"metallicFactor", 0}}}},
                      {{"name", "red"}, {"pbrMetallicRoughness", {{"baseColorFactor", {0.8, 0.2, 0.1, 1}}, {"metallicFactor", 0}}}},
                      {{"name", "lamp"}, {"emissiveFactor", {1, 1, 1}}}};
  doc["meshes"] = {{{"primitives", {quad_primitive(b, 0.0f, 2.0f, false, 0)}}},
                   {{"primitives", {cube_primitive(b, 1)}}},
                   {{"primitives", {quad_primitive(b, 2.0f, 0.4f, true, 2)}}}};
  doc["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.9}, {"znear", 0.05}}}}};
  doc["nodes"] = {{{"name", "floor"}, {"mesh", 0}},
                  {{"name", "mover"}, {"mesh", 1}, {"translation", {0, 0.3, 0}}, {"children", {2, 3}}},
                  {{"name", "child"}, {"mesh", 1}, {"translation", {0.8, 0.1, 0}}, {"scale", {0.5, 0.5, 0.5}}},
                  {{"name", "lamp"}, {"translation", {0, 0.9, 0}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}},
                  {{"name", "ceiling"}, {"mesh", 2}},
                  {{"name", "camera"}, {"camera", 0}, {"translation", {0.3, 1.2, 3.5}},
                   {"rotation", {-0.12, 0.0, 0.0, 0.9928}}}};
  doc["scene"] = 0;
  doc["scenes"] = {{{"nodes", {0, 1, 4, 5}}}};
  const float q = float(std::sqrt(0.5));
  const int times3 = b.floats({0.0f, 1.0f, 2.0f}, 1), moves = b.floats({0, 0.3f, 0, 0.6f, 0.4f, -0.2f, 0, 0.3f, 0}, 3);
  const int times2 = b.floats({0.0f, 2.0f}, 1);
  // CUBICSPLINE: in-tangent, value, out-tangent per key.
  const int turns = b.floats({0, 0, 0, 0, 0, 0, 0, 1, 0, 0.3f, 0, 0,  0, -0.2f, 0, 0, 0, q, 0, q, 0, 0, 0, 0}, 4);
  const int times_step = b.floats({0.0f, 0.5f}, 1), scales = b.floats({0.5f, 0.5f, 0.5f, 0.8f, 0.4f, 0.6f}, 3);
  doc["animations"] = {{{"samplers", {{{"input", times3}, {"output", moves}, {"interpolation", "LINEAR"}},
                                      {{"input", times2}, {"output", turns}, {"interpolation", "CUBICSPLINE"}},
                                      {{"input", times_step}, {"output", scales}, {"interpolation", "STEP"}}}},
                        {"channels", {{{"sampler", 0}, {"target", {{"node", 1}, {"path", "translation"}}}},
                                      {{"sampler", 1}, {"target", {{"node", 1}, {"path", "rotation"}}}},
                                      {{"sampler", 2}, {"target", {{"node", 2}, {"path", "scale"}}}}}}}};
  if (camera_moves) {
    const int flies = b.floats({0.3f, 1.2f, 3.5f, -0.6f, 1.5f, 3.0f}, 3);
    const int looks = b.floats({-0.12f, 0.0f, 0.0f, 0.9928f, -0.1f, 0.2f, 0.02f, 0.9744f}, 4);
    nlohmann::json& animation = doc["animations"][0];
    animation["samplers"].push_back({{"input", times2}, {"output", flies}, {"interpolation", "LINEAR"}});
    animation["samplers"].push_back({{"input", times2}, {"output", looks}, {"interpolation", "LINEAR"}});
    animation["channels"].push_back({{"sampler", 3}, {"target", {{"node", 5}, {"path", "translation"}}}});
    animation["channels"].push_back({{"sampler", 4}, {"target", {{"node", 5}, {"path", "rotation"}}}});
  }
  b.finish(doc);
  return doc;
}

// The document with its animation frozen at `time`: each moving node gets the
// translation, rotation and scale `animation` gives it then.
inline nlohmann::json posed_copy(nlohmann::json doc, const SceneAnimation& animation, double time) {
  doc.erase("animations");
  const std::vector<NodeTrs> locals = animation.locals(time);
  for (uint32_t i = 0; i < animation.nodes.size(); ++i) {
    const std::string& name = animation.nodes[i].name;  // "nodes[k]"
    const size_t k = std::stoul(name.substr(6, name.size() - 7));
    const NodeTrs& trs = locals[i];
    nlohmann::json& node = doc["nodes"][k];
    node["translation"] = {trs.translation.x, trs.translation.y, trs.translation.z};
    node["rotation"] = {trs.rotation.x, trs.rotation.y, trs.rotation.z, trs.rotation.w};
    node["scale"] = {trs.scale.x, trs.scale.y, trs.scale.z};
  }
  return doc;
}

}  // namespace igi::test
