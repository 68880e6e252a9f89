#pragma once
// The GGX (Trowbridge-Reitz) microfacet lobe, shared by the conductor and
// the metallic-roughness model. Local frame: z is the normal; directions
// are unit vectors pointing away from the surface.
//
// D is the distribution of normals, G2 = 1 / (1 + Lambda(wo) + Lambda(wi))
// the height-correlated Smith masking-shadowing (glTF's V = G2 / (4 |n.wo|
// |n.wi|)), and directions are sampled from the normals visible from wo
// (Heitz 2018), pdf(wi) = G1(wo) D(h) / (4 wo.z).
#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

#include "sampling/warp.h"

namespace igi {

inline float ggx_d(glm::vec3 h, float alpha) {
  float a2 = alpha * alpha;
  float c2 = h.z * h.z;
  float denom = c2 * (a2 - 1.0f) + 1.0f;
  return a2 / (kPi * denom * denom);
}

inline float ggx_lambda(glm::vec3 w, float alpha) {
  float c2 = w.z * w.z;
  if (c2 <= 0.0f) return 0.0f;
  float tan2 = std::max(0.0f, 1.0f - c2) / c2;
  return 0.5f * (std::sqrt(1.0f + alpha * alpha * tan2) - 1.0f);
}

inline float ggx_g1(glm::vec3 w, float alpha) { return 1.0f / (1.0f + ggx_lambda(w, alpha)); }
inline float ggx_g2(glm::vec3 wo, glm::vec3 wi, float alpha) {
  return 1.0f / (1.0f + ggx_lambda(wo, alpha) + ggx_lambda(wi, alpha));
}

// Visible-normal sampling (Heitz 2018), wo in the upper hemisphere.
inline glm::vec3 ggx_sample_visible_normal(glm::vec3 wo, float alpha, glm::vec2 u) {
  glm::vec3 vh = glm::normalize(glm::vec3(alpha * wo.x, alpha * wo.y, wo.z));
  float len2 = vh.x * vh.x + vh.y * vh.y;
  glm::vec3 t1 = len2 > 0.0f ? glm::vec3(-vh.y, vh.x, 0.0f) / std::sqrt(len2) : glm::vec3(1, 0, 0);
  glm::vec3 t2 = glm::cross(vh, t1);
  float r = std::sqrt(u.x), phi = 2.0f * kPi * u.y;
  float p1 = r * std::cos(phi), p2 = r * std::sin(phi);
  float s = 0.5f * (1.0f + vh.z);
  p2 = (1.0f - s) * std::sqrt(std::max(0.0f, 1.0f - p1 * p1)) + s * p2;
  glm::vec3 nh = p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0f, 1.0f - p1 * p1 - p2 * p2)) * vh;
  return glm::normalize(glm::vec3(alpha * nh.x, alpha * nh.y, std::max(1e-6f, nh.z)));
}

// The density of wi = reflect(wo, h) for h drawn by ggx_sample_visible_normal.
inline float ggx_reflection_pdf(glm::vec3 wo, glm::vec3 wi, float alpha) {
  if (wo.z <= 0.0f || wi.z <= 0.0f) return 0.0f;
  glm::vec3 h = glm::normalize(wo + wi);
  return ggx_g1(wo, alpha) * ggx_d(h, alpha) / (4.0f * wo.z);
}

// D G2 / (4 cos_o cos_i): the lobe with a Fresnel of 1.
inline float ggx_lobe(glm::vec3 wo, glm::vec3 wi, glm::vec3 h, float alpha) {
  return ggx_d(h, alpha) * ggx_g2(wo, wi, alpha) / (4.0f * wo.z * wi.z);
}

inline glm::vec3 reflect(glm::vec3 wo, glm::vec3 n) { return 2.0f * glm::dot(wo, n) * n - wo; }

// Schlick's Fresnel weight (1 - cos)^5.
inline float schlick_weight(float cos_theta) {
  const float m = std::clamp(1.0f - cos_theta, 0.0f, 1.0f);
  const float m2 = m * m;
  return m2 * m2 * m;
}

}  // namespace igi
