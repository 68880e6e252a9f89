#pragma once
// Maps from the unit square to directions and points, with their densities.
#include <cmath>
#include <numbers>

#include <glm/glm.hpp>

namespace igi {

inline constexpr float kPi = std::numbers::pi_v<float>;
inline constexpr float kInvPi = 1.0f / kPi;
inline constexpr float kInv4Pi = 0.25f / kPi;

// Orthonormal basis (t, b, n) around a unit normal n (Duff et al. 2017).
struct Onb {
  glm::vec3 t, b, n;
  explicit Onb(glm::vec3 normal) : n(normal) {
    float sign = std::copysign(1.0f, n.z);
    float a = -1.0f / (sign + n.z);
    float c = n.x * n.y * a;
    t = glm::vec3(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
    b = glm::vec3(c, sign + n.y * n.y * a, -n.y);
  }
  glm::vec3 to_world(glm::vec3 v) const { return v.x * t + v.y * b + v.z * n; }
  glm::vec3 to_local(glm::vec3 v) const { return {glm::dot(v, t), glm::dot(v, b), glm::dot(v, n)}; }
};

// Multiple importance sampling's power heuristic (beta 2): the weight of a
// sample drawn with density a against another technique's density b.
inline float power_heuristic(float a, float b) { return a * a / (a * a + b * b); }

// Cosine-weighted hemisphere around +z; density cos(theta)/pi.
inline glm::vec3 cosine_hemisphere(glm::vec2 u) {
  float r = std::sqrt(u.x), phi = 2.0f * kPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0f, 1.0f - u.x))};
}

// Uniform direction on the unit sphere; density 1 / (4 pi).
inline glm::vec3 uniform_sphere(glm::vec2 u) {
  float z = 1.0f - 2.0f * u.x, r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  return {r * std::cos(2.0f * kPi * u.y), r * std::sin(2.0f * kPi * u.y), z};
}

// Uniform point on a triangle as barycentrics (b1, b2) (Heitz 2019: low distortion).
inline glm::vec2 uniform_triangle(glm::vec2 u) {
  if (u.y > u.x) { u.x *= 0.5f; u.y -= u.x; }
  else { u.y *= 0.5f; u.x -= u.y; }
  return u;
}

// Uniform direction inside a cone of half-angle acos(cos_max) around +z.
inline glm::vec3 uniform_cone(glm::vec2 u, float cos_max) {
  float cos_theta = 1.0f - u.x * (1.0f - cos_max);
  float sin_theta = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta));
  float phi = 2.0f * kPi * u.y;
  return {sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta};
}

inline float luminance(glm::vec3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }
inline float max_component(glm::vec3 c) { return std::max(c.x, std::max(c.y, c.z)); }

}  // namespace igi
