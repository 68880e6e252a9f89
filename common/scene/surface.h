#pragma once
// What shading needs to know about a ray hit, resolved once per hit.
#include <glm/glm.hpp>

#include "scene/accel.h"
#include "scene/scene.h"

namespace igi {

struct SurfacePoint {
  glm::vec3 position;
  glm::vec3 geometric_normal;  // unit, front side (counter-clockwise winding)
  glm::vec3 shading_normal;    // unit, interpolated; on the same side as geometric_normal
  glm::vec2 uv{0.0f};
  uint32_t triangle = 0;
  const Material* material = nullptr;
  glm::vec3 albedo{0.0f};      // base colour times texture, linear
  // MetallicRoughness: the material's metallic and GGX alpha here (its
  // metallic-roughness texture applied); others: metallic 0 and the material's alpha.
  float metallic = 0.0f;
  float alpha = 1.0f;
  bool front_face = true;      // whether the ray arrived on the front side

  // Radiance leaving the surface towards -ray_direction (front face only).
  glm::vec3 emitted() const { return front_face ? material->emission : glm::vec3(0.0f); }

  // The normals turned to the side of the geometric surface that `wo` leaves
  // from (the viewer's side, for a camera hit): the hemisphere shading uses.
  bool faces(glm::vec3 wo) const { return glm::dot(wo, geometric_normal) >= 0.0f; }
  glm::vec3 shading_normal_facing(glm::vec3 wo) const { return faces(wo) ? shading_normal : -shading_normal; }
  glm::vec3 geometric_normal_facing(glm::vec3 wo) const { return faces(wo) ? geometric_normal : -geometric_normal; }
};

// The surface a ray met: position, normals (the shading normal bent by the
// material's normal map, if any), uv, and the material's textured values.
SurfacePoint surface_at(const Scene& scene, const Hit& hit, glm::vec3 ray_direction);

// A ray origin nudged off the surface, to the side `direction` leaves from,
// so the new ray does not re-hit the triangle it starts on.
glm::vec3 offset_origin(const SurfacePoint& sp, glm::vec3 direction);
// `p` nudged along the unit vector `n` by offset_origin's distance (which
// grows with the coordinates' magnitude, as their rounding does).
glm::vec3 offset_point(glm::vec3 p, glm::vec3 n);
// tfar that stops a shadow ray just short of `target`, relative to its length.
inline constexpr float kShadowEpsilon = 1e-4f;

// The shadow ray from sp towards `target` (direction wi from sp, `distance`
// away; infinity for a directional light, which has no target). It is aimed
// from the nudged origin at the target itself, not along wi: a ray shifted
// parallel to wi meets the target's surface before the target wherever that
// surface is seen at a grazing angle (by offset x cos between the normals /
// cos at the target), and that false occlusion hid a tilted area light from
// every wall beside it.
Ray shadow_ray(const SurfacePoint& sp, glm::vec3 wi, glm::vec3 target, float distance);

}  // namespace igi
