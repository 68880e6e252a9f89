#pragma once
// Every light of a scene in one list, chosen in proportion to its power:
// emissive triangles (area lights, front face only), punctual lights and
// the environment (Scene::environment, a constant sky or a map; last in the list).
//
// Units: area-light radiance W/(m^2 sr); point/spot intensity W/sr;
// directional irradiance W/m^2; environment radiance W/(m^2 sr). Power is
// the luminance of the emitted flux; the environment's is what enters the
// scene's bounding sphere of radius R, pi R^2 x the integral of L over the
// sphere (4 pi^2 R^2 L for a constant sky, as pbrt-v4 counts it).
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "sampling/distribution.h"
#include "scene/scene.h"

namespace igi {

enum class LightKind : uint8_t { Area, Point, Spot, Directional, Environment };

struct Light {
  LightKind kind;
  uint32_t index;  // triangle (Area), Scene::lights entry (punctual), 0 (Environment)
};

// A point on a light as seen from a shading point, for next-event estimation.
struct LightSample {
  glm::vec3 direction;    // unit, from the shading point towards the light
  float distance = 0.0f;  // infinity for directional lights
  glm::vec3 position{0.0f};  // the point on the light (area) or the light (point, spot); unused for directional
  glm::vec3 radiance;     // incident radiance (area) or irradiance-normalised intensity / r^2 (delta)
  float pdf = 0.0f;       // solid-angle density including selection; selection prob for delta lights
  bool delta = false;
};

// A ray leaving a light, for tracing light paths (VPLs).
struct EmissionSample {
  glm::vec3 position;
  glm::vec3 normal;     // area: surface normal; point/spot/environment: zero; directional: travel direction
  glm::vec3 power;      // flux carried by this path: emitted quantity / (pdf of choosing it)
  LightKind kind;
  uint32_t light;       // index into LightSet::lights()
};

class LightSet {
 public:
  explicit LightSet(const Scene& scene);
  // After the scene's lights moved (scene/animation.h): re-weighs them, with
  // `bounds` the scene's bounds as posed (directional lights cover them).
  // The list of lights stays as built. Not while sampling.
  void refresh(const Bounds& bounds);

  const std::vector<Light>& lights() const { return lights_; }
  bool empty() const { return lights_.empty(); }
  float selection_probability(uint32_t light) const { return distribution_.probability(light); }
  // The lights in proportion to their power: how light paths choose one by default.
  const Distribution1D& power_distribution() const { return distribution_; }

  // Next-event estimation from point p. u_select picks the light; u picks the point.
  LightSample sample(glm::vec3 p, float u_select, glm::vec2 u) const;
  // The same for a light the caller chose, with probability `select` (folded into pdf).
  LightSample sample_light(uint32_t light, float select, glm::vec3 p, glm::vec2 u) const;
  // Solid-angle density with which sample() would have picked the point hit on
  // emissive `triangle` at `hit_point` from `p` (for MIS of BSDF-sampled hits).
  float pdf_area(uint32_t triangle, glm::vec3 p, glm::vec3 hit_point) const;
  // Solid-angle density with which sample() picks `direction` (towards the
  // sky) of the environment: uniform over the sphere for a constant sky, by
  // luminance for a map; 0 without one.
  float pdf_environment(glm::vec3 direction) const;

  // A direction towards the sky (uniform, or by the map's luminance) and the
  // radiance from it; pdf in solid angle, without the light's selection.
  struct SkySample {
    glm::vec3 direction{0.0f};
    glm::vec3 radiance{0.0f};
    float pdf = 0.0f;
  };
  SkySample sample_sky(glm::vec2 u) const;

  // A light and a point on it, with the power it carries (for VPL light paths).
  // Area lights: point uniform on the triangle; the direction is sampled by
  // the caller. The environment: power is its radiance scale / selection,
  // the caller samples a direction (sample_sky) and the disc across it.
  EmissionSample sample_emission(float u_select, glm::vec2 u) const;
  // The same with the light chosen by `selection` (one weight per light, e.g.
  // light importance) instead of by power; power is divided by its probability.
  EmissionSample sample_emission(const Distribution1D& selection, float u_select, glm::vec2 u) const;
  // The same for light `light`, chosen by the caller with probability `select`.
  EmissionSample sample_emission_at(uint32_t light, float select, glm::vec2 u) const;
  // Emitted power of light `light` (luminance of its flux): the weights of power selection.
  float light_power(uint32_t light) const { return power(lights_[light]); }

  // Where a ray entering the scene along `direction` (unit) starts: on the
  // disc of the scene's radius across it, outside the scene, u uniform on
  // the disc (directional lights and the environment).
  glm::vec3 disc_origin(glm::vec3 direction, glm::vec2 u) const;

  float scene_radius() const { return scene_radius_; }
  const Scene& scene() const { return scene_; }
  float triangle_area(uint32_t triangle) const;

 private:
  float power(const Light& light) const;
  // The environment's flux into the scene: pi R^2 (the disc across each
  // direction) x the radiance integrated over the sphere.
  glm::vec3 sky_flux() const;

  const Scene& scene_;
  std::vector<Light> lights_;
  std::vector<int32_t> light_of_triangle_;  // -1 when not emissive
  Distribution1D distribution_;
  int32_t environment_ = -1;  // its index in lights_, -1 when the scene has none
  glm::vec3 scene_center_;
  float scene_radius_ = 1.0f;
};

// Spot cone attenuation as in the KHR_lights_punctual reference (smooth, squared).
float spot_attenuation(const PunctualLight& light, glm::vec3 direction_from_light);

}  // namespace igi
