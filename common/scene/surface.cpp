#include "scene/surface.h"

#include <algorithm>
#include <cmath>

#include "scene/triangle.h"

namespace igi {

namespace {

// A tangent-space normal map's normal at sp (glTF normalTexture): n =
// normalize(T x + B y + N z) with (x, y, z) = (2 t - 1) (scale, scale, 1).
// T and B come from the triangle's uv layout: T along increasing u, B
// along decreasing v (glTF's v runs down the image, its normal maps' y
// up), both made orthogonal to the interpolated normal N, as MikkTSpace
// makes them where uvs are not sheared. A map that would tip the normal
// below the surface, or a triangle without a uv layout, keeps N.
glm::vec3 mapped_normal(const Scene& scene, const glm::uvec3& t, const SurfacePoint& sp, const Material& m) {
  const glm::vec3 dp1 = scene.positions[t[1]] - scene.positions[t[0]];
  const glm::vec3 dp2 = scene.positions[t[2]] - scene.positions[t[0]];
  const glm::vec2 duv1 = scene.uvs[t[1]] - scene.uvs[t[0]], duv2 = scene.uvs[t[2]] - scene.uvs[t[0]];
  const float det = duv1.x * duv2.y - duv1.y * duv2.x;
  const glm::vec3 n = sp.shading_normal;
  if (!(std::abs(det) > 0.0f)) return n;
  const glm::vec3 dpdu = (dp1 * duv2.y - dp2 * duv1.y) / det;
  const glm::vec3 dpdv = (dp2 * duv1.x - dp1 * duv2.x) / det;
  const glm::vec3 along = dpdu - n * glm::dot(n, dpdu);
  const float length = glm::length(along);
  if (!(length > 0.0f) || !std::isfinite(length)) return n;
  const glm::vec3 tangent = along / length;
  glm::vec3 bitangent = glm::cross(n, tangent);
  if (glm::dot(bitangent, dpdv) > 0.0f) bitangent = -bitangent;  // mirrored uvs
  const glm::vec4 texel = scene.textures[size_t(m.normal_texture.index)].sample(m.normal_texture.uv(sp.uv));
  const glm::vec3 local((2.0f * texel.x - 1.0f) * m.normal_scale, (2.0f * texel.y - 1.0f) * m.normal_scale,
                        2.0f * texel.z - 1.0f);
  const glm::vec3 bent = local.x * tangent + local.y * bitangent + local.z * n;
  const float bent_length = glm::length(bent);
  if (!(bent_length > 0.0f) || !std::isfinite(bent_length)) return n;
  const glm::vec3 out = bent / bent_length;
  return glm::dot(out, sp.geometric_normal) > 0.0f ? out : n;
}

// The metallic-roughness model's values at sp (Material says how).
void resolve_metallic_roughness(const Scene& scene, const glm::uvec3& t, const Material& m, SurfacePoint& sp) {
  auto lookup = [&](const TextureRef& ref) { return scene.textures[size_t(ref.index)].sample(ref.uv(sp.uv)); };
  float metallic = m.metallic, roughness = m.roughness;
  if (m.metallic_roughness_texture.used()) {
    const glm::vec4 texel = lookup(m.metallic_roughness_texture);
    if (!m.metallic_texture.used()) metallic *= texel.z;
    if (!m.roughness_texture.used()) roughness *= texel.y;
  }
  if (m.metallic_texture.used()) metallic *= lookup(m.metallic_texture).z;
  if (m.roughness_texture.used()) roughness *= lookup(m.roughness_texture).y;
  sp.metallic = std::clamp(metallic, 0.0f, 1.0f);
  sp.alpha = std::max(roughness * roughness, kMinMetallicRoughnessAlpha);
  if (m.normal_texture.used() && !scene.uvs.empty()) sp.shading_normal = mapped_normal(scene, t, sp, m);
}

}  // namespace

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
  const Material& m = scene.materials[scene.triangle_material[hit.triangle]];
  sp.material = &m;
  sp.albedo = m.base_color;
  if (m.base_color_texture.used())
    sp.albedo *= glm::vec3(scene.textures[size_t(m.base_color_texture.index)].sample(m.base_color_texture.uv(sp.uv)));
  sp.alpha = m.alpha;
  if (m.type == MaterialType::MetallicRoughness) resolve_metallic_roughness(scene, t, m, sp);
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
