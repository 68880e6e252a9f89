#include "lighting/lights.h"

#include <cmath>

#include "sampling/warp.h"
#include "scene/triangle.h"

namespace igi {

float spot_attenuation(const PunctualLight& light, glm::vec3 direction_from_light) {
  float cos_outer = std::cos(light.outer_cone), cos_inner = std::cos(light.inner_cone);
  float scale = 1.0f / std::max(0.001f, cos_inner - cos_outer);
  float cd = glm::dot(glm::normalize(light.direction), direction_from_light);
  float a = glm::clamp((cd - cos_outer) * scale, 0.0f, 1.0f);
  return a * a;
}

LightSet::LightSet(const Scene& scene) : scene_(scene), light_of_triangle_(scene.triangles.size(), -1) {
  for (uint32_t i = 0; i < scene.triangles.size(); ++i)
    if (scene.materials[scene.triangle_material[i]].is_emissive() && triangle_area(i) > 0.0f) {
      light_of_triangle_[i] = int32_t(lights_.size());
      lights_.push_back({LightKind::Area, i});
    }
  for (uint32_t i = 0; i < scene.lights.size(); ++i) {
    static constexpr LightKind kinds[] = {LightKind::Point, LightKind::Spot, LightKind::Directional};
    lights_.push_back({kinds[int(scene.lights[i].type)], i});
  }
  if (scene.has_environment()) {
    environment_ = int32_t(lights_.size());
    lights_.push_back({LightKind::Environment, 0});
  }
  refresh(scene.bounds());
}

void LightSet::refresh(const Bounds& b) {
  scene_center_ = b.empty() ? glm::vec3(0.0f) : b.center();
  scene_radius_ = b.empty() ? 1.0f : std::max(1e-6f, 0.5f * b.diagonal());
  std::vector<float> weights;
  for (const Light& l : lights_) weights.push_back(power(l));
  distribution_ = Distribution1D(weights);
}

float LightSet::triangle_area(uint32_t triangle) const {
  return 0.5f * glm::length(triangle_cross(scene_, triangle));
}

float LightSet::power(const Light& light) const {
  if (light.kind == LightKind::Area) {
    const Material& m = scene_.materials[scene_.triangle_material[light.index]];
    return luminance(m.emission) * triangle_area(light.index) * kPi;
  }
  if (light.kind == LightKind::Environment) return luminance(sky_flux());
  const PunctualLight& p = scene_.lights[light.index];
  float i = luminance(p.intensity);
  switch (light.kind) {
    case LightKind::Point: return 4.0f * kPi * i;
    case LightKind::Spot: return 2.0f * kPi * (1.0f - std::cos(0.5f * (p.inner_cone + p.outer_cone))) * i;
    default: return kPi * scene_radius_ * scene_radius_ * i;
  }
}

LightSample LightSet::sample(glm::vec3 p, float u_select, glm::vec2 u) const {
  if (lights_.empty()) return LightSample{};
  uint32_t index = distribution_.sample(u_select);
  return sample_light(index, distribution_.probability(index), p, u);
}

LightSample LightSet::sample_light(uint32_t index, float select, glm::vec3 p, glm::vec2 u) const {
  LightSample s;
  const Light& light = lights_[index];
  if (light.kind == LightKind::Area) {
    const glm::uvec3& t = scene_.triangles[light.index];
    glm::vec3 p0 = scene_.positions[t[0]], p1 = scene_.positions[t[1]], p2 = scene_.positions[t[2]];
    glm::vec2 b = uniform_triangle(u);
    glm::vec3 q = (1.0f - b.x - b.y) * p0 + b.x * p1 + b.y * p2;
    glm::vec3 n = triangle_normal(p0, p1, p2);
    glm::vec3 d = q - p;
    float dist2 = glm::dot(d, d);
    s.distance = std::sqrt(dist2);
    s.direction = d / s.distance;
    s.position = q;
    float cos_light = -glm::dot(n, s.direction);
    if (cos_light <= 0.0f || dist2 <= 0.0f) return LightSample{};  // back face emits nothing
    s.radiance = scene_.materials[scene_.triangle_material[light.index]].emission;
    s.pdf = select * dist2 / (cos_light * triangle_area(light.index));
    return s;
  }
  if (light.kind == LightKind::Environment) {
    const SkySample sky = sample_sky(u);
    if (sky.pdf <= 0.0f) return LightSample{};
    s.direction = sky.direction;
    s.distance = INFINITY;
    s.radiance = sky.radiance;
    s.pdf = select * sky.pdf;
    return s;
  }
  const PunctualLight& pl = scene_.lights[light.index];
  s.delta = true;
  s.pdf = select;
  if (light.kind == LightKind::Directional) {
    s.direction = -glm::normalize(pl.direction);
    s.distance = INFINITY;
    s.radiance = pl.intensity;
    return s;
  }
  glm::vec3 d = pl.position - p;
  float dist2 = glm::dot(d, d);
  s.distance = std::sqrt(dist2);
  s.direction = d / s.distance;
  s.position = pl.position;
  float falloff = light.kind == LightKind::Spot ? spot_attenuation(pl, -s.direction) : 1.0f;
  s.radiance = pl.intensity * (falloff / dist2);
  return s;
}

float LightSet::pdf_area(uint32_t triangle, glm::vec3 p, glm::vec3 hit_point) const {
  int32_t light = light_of_triangle_[triangle];
  if (light < 0) return 0.0f;
  glm::vec3 n = triangle_normal(scene_, triangle);
  glm::vec3 d = hit_point - p;
  float dist2 = glm::dot(d, d);
  float cos_light = std::abs(glm::dot(n, d)) / std::sqrt(dist2);
  if (cos_light <= 0.0f) return 0.0f;
  return distribution_.probability(uint32_t(light)) * dist2 / (cos_light * triangle_area(triangle));
}

glm::vec3 LightSet::sky_flux() const {
  const glm::vec3 over_sphere =
      scene_.environment * (scene_.environment_map ? scene_.environment_map->integral() : glm::vec3(4.0f * kPi));
  return over_sphere * (kPi * scene_radius_ * scene_radius_);
}

LightSet::SkySample LightSet::sample_sky(glm::vec2 u) const {
  if (!scene_.environment_map) return {uniform_sphere(u), scene_.environment, kInv4Pi};  // nothing brighter to aim at
  const EnvironmentMap::Sample s = scene_.environment_map->sample(u);
  return {s.direction, scene_.environment * s.radiance, s.pdf};
}

float LightSet::pdf_environment(glm::vec3 direction) const {
  if (environment_ < 0) return 0.0f;
  const float pdf = scene_.environment_map ? scene_.environment_map->pdf(direction) : kInv4Pi;
  return distribution_.probability(uint32_t(environment_)) * pdf;
}

glm::vec3 LightSet::disc_origin(glm::vec3 direction, glm::vec2 u) const {
  const Onb frame(direction);
  const float r = std::sqrt(u.x) * scene_radius_, phi = 2.0f * kPi * u.y;
  return scene_center_ - direction * scene_radius_ + frame.to_world({r * std::cos(phi), r * std::sin(phi), 0.0f});
}

EmissionSample LightSet::sample_emission(float u_select, glm::vec2 u) const {
  return sample_emission(distribution_, u_select, u);
}

EmissionSample LightSet::sample_emission(const Distribution1D& selection, float u_select, glm::vec2 u) const {
  const uint32_t index = selection.sample(u_select);
  return sample_emission_at(index, selection.probability(index), u);
}

EmissionSample LightSet::sample_emission_at(uint32_t index, float select, glm::vec2 u) const {
  const Light& light = lights_[index];
  EmissionSample e{};
  e.kind = light.kind;
  e.light = index;
  if (light.kind == LightKind::Area) {
    const glm::uvec3& t = scene_.triangles[light.index];
    glm::vec3 p0 = scene_.positions[t[0]], p1 = scene_.positions[t[1]], p2 = scene_.positions[t[2]];
    glm::vec2 b = uniform_triangle(u);
    e.position = (1.0f - b.x - b.y) * p0 + b.x * p1 + b.y * p2;
    e.normal = triangle_normal(p0, p1, p2);
    // Radiance times area: the VPL's emitted radiance per unit projected solid angle.
    e.power = scene_.materials[scene_.triangle_material[light.index]].emission *
              (triangle_area(light.index) / select);
    return e;
  }
  if (light.kind == LightKind::Environment) {
    // The direction is the caller's (sample_sky), the origin on the disc
    // across it: flux L / pdf (directions) x pi R^2 (the disc), per choice.
    e.position = glm::vec3(0.0f);
    e.normal = glm::vec3(0.0f);
    e.power = glm::vec3(1.0f / select);
    return e;
  }
  const PunctualLight& pl = scene_.lights[light.index];
  if (light.kind == LightKind::Directional) {
    // A point on a disc of the scene's radius facing the light, outside the scene.
    glm::vec3 dir = glm::normalize(pl.direction);
    e.position = disc_origin(dir, u);
    e.normal = dir;
    e.power = pl.intensity * (kPi * scene_radius_ * scene_radius_ / select);
    return e;
  }
  e.position = pl.position;
  e.normal = glm::vec3(0.0f);
  e.power = pl.intensity / select;  // intensity per steradian; direction chosen by the caller
  return e;
}

}  // namespace igi
