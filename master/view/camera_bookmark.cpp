#include "view/camera_bookmark.h"

#include <cmath>
#include <fstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

namespace igi {
namespace {

constexpr float kDegrees = 180.0f / 3.14159265358979f;

glm::vec3 read_vec3(const nlohmann::json& j, const std::string& path, const char* field) {
  auto fail = [&] { throw std::runtime_error(path + ": \"" + field + "\": expected an array of 3 finite numbers"); };
  if (!j.contains(field) || !j[field].is_array() || j[field].size() != 3) fail();
  glm::vec3 v;
  for (int i = 0; i < 3; ++i) {
    if (!j[field][i].is_number()) fail();
    v[i] = j[field][i].get<float>();
    if (!std::isfinite(v[i])) fail();
  }
  return v;
}

}  // namespace

Camera read_camera_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot read the camera file");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(path + ": not JSON (" + e.what() + ")");
  }
  if (!j.is_object()) throw std::runtime_error(path + ": expected a JSON object with position, forward, up, vfov_degrees");
  Camera c;
  c.position = read_vec3(j, path, "position");
  c.forward = read_vec3(j, path, "forward");
  c.up = read_vec3(j, path, "up");
  if (glm::length(c.forward) < 1e-6f) throw std::runtime_error(path + ": \"forward\": must not be zero");
  if (glm::length(glm::cross(c.forward, c.up)) < 1e-6f * glm::length(c.forward) * glm::length(c.up))
    throw std::runtime_error(path + ": \"up\": must not be zero or parallel to forward");
  if (!j.contains("vfov_degrees") || !j["vfov_degrees"].is_number())
    throw std::runtime_error(path + ": \"vfov_degrees\": expected a number in (0, 180)");
  const float degrees = j["vfov_degrees"].get<float>();
  if (!(degrees > 0.0f && degrees < 180.0f))
    throw std::runtime_error(path + ": \"vfov_degrees\": expected a number in (0, 180)");
  c.vfov = degrees / kDegrees;
  return c;
}

void write_camera_file(const std::string& path, const Camera& c) {
  auto array = [](glm::vec3 v) { return nlohmann::json::array({v.x, v.y, v.z}); };
  const nlohmann::json j = {{"position", array(c.position)}, {"forward", array(c.forward)}, {"up", array(c.up)},
                            {"vfov_degrees", c.vfov * kDegrees}};
  std::ofstream out(path);
  out << j.dump(2) << "\n";
  if (!out) throw std::runtime_error(path + ": cannot write the camera file");
}

}  // namespace igi
