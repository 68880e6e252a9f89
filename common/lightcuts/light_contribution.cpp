#include "lightcuts/light_contribution.h"

#include <cmath>

#include "core/clamp.h"
#include "lighting/lights.h"
#include "material/bsdf.h"
#include "sampling/warp.h"

namespace igi::lightcuts {
namespace {

// The BSDF at the gather point, albedo included: bsdf_eval's rule, as every
// VPL method shades (core/vpl_contribution.h).
glm::vec3 receiver_bsdf(const GatherPoint& g, glm::vec3 wi) { return bsdf_eval(g.surface, g.wo, wi); }

// A surface VPL's BSDF, light arriving from its incident direction and
// leaving along `out`; with `white`, albedo 1 (what the clamp bounds).
glm::vec3 vpl_bsdf(const Scene& scene, const Vpl& v, glm::vec3 out, bool white = false) {
  SurfacePoint sp;
  sp.position = v.position;
  sp.geometric_normal = sp.shading_normal = v.normal;
  sp.material = &scene.materials[v.material];
  sp.albedo = white ? glm::vec3(1.0f) : v.albedo;
  return bsdf_eval(sp, v.incident, out);
}

}  // namespace

glm::vec3 light_contribution(const LightingContext& context, const GatherPoint& g, const LightLeaf& leaf,
                             Ray& shadow) {
  const SurfacePoint& sp = g.surface;
  glm::vec3 wi, emitted;
  float g_term, distance;
  if (leaf.light_class == LightClass::Directional) {
    wi = leaf.position;
    distance = INFINITY;
    g_term = std::abs(glm::dot(wi, sp.shading_normal));
    emitted = leaf.intensity;
  } else {
    const glm::vec3 d = leaf.position - sp.position;
    const float dist2 = glm::dot(d, d);
    distance = std::sqrt(dist2);
    wi = d / distance;
    const float cos_x = std::abs(glm::dot(wi, sp.shading_normal));
    if (leaf.light_class == LightClass::Punctual) {
      g_term = cos_x / dist2;  // exact point and spot lights: never clamped
      const PunctualLight& light = context.scene.lights[leaf.source];
      emitted = light.type == LightType::Spot ? leaf.intensity * spot_attenuation(light, -wi) : leaf.intensity;
    } else {
      const float cos_y = -glm::dot(wi, leaf.normal);
      if (cos_y <= 0.0f) return glm::vec3(0.0f);
      g_term = std::min(cos_x * cos_y / dist2, context.clamp_bound);
      emitted = leaf.light_class == LightClass::Glossy
                    ? vpl_bsdf(context.scene, context.vpls[leaf.source], -wi) * leaf.intensity
                    : leaf.intensity;
      // A glossy VPL's lobe is clamped as a glossy receiver's (core/clamp.h), as ir and igi take it.
      if (leaf.light_class == LightClass::Glossy && context.clamp_bound < INFINITY)
        emitted *= glossy_lobe_clamp(max_component(vpl_bsdf(context.scene, context.vpls[leaf.source], -wi, true)),
                                     g_term, context.clamp_bound);
    }
  }
  glm::vec3 f = receiver_bsdf(g, wi);
  // A glossy receiver's clamp (core/clamp.h), on its BSDF with albedo 1, as ir and igi take it.
  if (leaf.light_class != LightClass::Punctual && leaf.light_class != LightClass::Directional &&
      sp.material->type == MaterialType::Conductor && context.clamp_bound < INFINITY) {
    SurfacePoint white = sp;
    white.albedo = glm::vec3(1.0f);
    f *= glossy_lobe_clamp(max_component(bsdf_eval(white, g.wo, wi)), g_term, context.clamp_bound);
  }
  const glm::vec3 c = f * emitted * g_term;
  // Nothing, or a light on the point itself (unclamped: infinite or NaN).
  if (!(c.x + c.y + c.z > 0.0f) || !std::isfinite(c.x + c.y + c.z)) return glm::vec3(0.0f);
  shadow = shadow_ray(sp, wi, leaf.position, distance);
  return c;
}

}  // namespace igi::lightcuts
