#include "scene/surface.h"

#include <cmath>

#include "scene/triangle.h"

namespace igi {

SurfacePoint surface_at(const Scene& scene, const Hit& hit, glm::vec3 ray_direction) {
  SurfacePoint sp;
  const glm::uvec3& t = scene.triangles[hit.triangle];
  const glm::vec3 p0 = scene.positions[t[0]], p1 = scene.positions[t[1]], p2 = scene.positions[t[2]];
  const float b1 = hit.barycentric.x, b2 = hit.barycentric.y, b0 = 1.0f - b1 - b2;
  sp.position = b0 * p0 + b1 * p1 + b2 * p2;
  sp.geometric_normal = triangle_normal(p0, p1, p2);
  sp.shading_normal = sp.geometric_normal;
  if (!scene.normals.empty()) {
    glm::vec3 n = b0 * scene.normals[t[0]] + b1 * scene.normals[t[1]] + b2 * scene.normals[t[2]];
    float len = glm::length(n);
    if (len > 0.0f && std::isfinite(len)) {
      n /= len;
      sp.shading_normal = glm::dot(n, sp.geometric_normal) < 0.0f ? -n : n;
    }
  }
  if (!scene.uvs.empty()) sp.uv = b0 * scene.uvs[t[0]] + b1 * scene.uvs[t[1]] + b2 * scene.uvs[t[2]];
  sp.triangle = hit.triangle;
  sp.material = &scene.materials[scene.triangle_material[hit.triangle]];
  sp.albedo = sp.material->base_color;
  if (sp.material->base_color_texture >= 0)
    sp.albedo *= glm::vec3(scene.textures[sp.material->base_color_texture].sample(sp.uv));
  sp.front_face = glm::dot(ray_direction, sp.geometric_normal) < 0.0f;
  return sp;
}

glm::vec3 offset_point(glm::vec3 p, glm::vec3 n) {
  float scale = std::max(std::max(std::abs(p.x), std::abs(p.y)), std::abs(p.z));
  float eps = 2e-5f * scale + 1e-7f;
  return p + eps * n;
}

glm::vec3 offset_origin(const SurfacePoint& sp, glm::vec3 direction) {
  const glm::vec3 n = sp.geometric_normal;
  return offset_point(sp.position, glm::dot(direction, n) >= 0.0f ? n : -n);
}

Ray shadow_ray(const SurfacePoint& sp, glm::vec3 wi, glm::vec3 target, float distance) {
  const glm::vec3 origin = offset_origin(sp, wi);
  if (std::isinf(distance)) return Ray{origin, wi, 0.0f, INFINITY};
  const glm::vec3 d = target - origin;
  const float length = glm::length(d);
  if (!(length > 0.0f)) return Ray{origin, wi, 0.0f, 0.0f};
  return Ray{origin, d / length, 0.0f, length * (1.0f - kShadowEpsilon)};
}

}  // namespace igi
