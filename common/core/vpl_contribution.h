#pragma once
// The one VPL shading rule: unoccluded light from one VPL (or one exact
// light, as a Vpl of its kind: core/direct_lights.h) to one shading point,
// demodulated (the BSDF at the shading point divided by material/bsdf.h's
// modulation, the albedo for all but the metallic-roughness model; ir and
// igi multiply the filtered result by the modulation once, lightcuts each
// term). Every VPL method shades through it: ir and igi (the general lanes;
// the vectorised diffuse lanes of methods/shadow_batch.cpp equal it bit for
// bit), lightcuts (lightcuts/light_contribution.h), bidirectional IR, bias
// compensation and the light tree's draws. See core/vpl.h for the terms.
#include <cmath>

#include "core/clamp.h"
#include "core/gbuffer.h"
#include "core/vpl.h"
#include "material/bsdf.h"
#include "sampling/warp.h"

namespace igi {

// Where a shadow ray to `v` aims: a VPL that lies on a surface (a bounce, or
// a point of an area light), nudged off that surface to its lit side as the
// ray's origin is nudged off its own. Aimed at the VPL itself, a ray from a
// point of the same wall ran along the wall and ended 1e-4 of its length
// short of the VPL: within a rounding of the wall's plane, where Embree's
// 16-wide packets and single rays answered differently (the packet tests a
// lane against every triangle of the leaves its neighbours reach). The light
// such a ray carries is nil (cos at the receiver about 1e-3); what changes is
// that its answer no longer depends on the packet (methods/shadow_batch.cpp).
inline glm::vec3 shadow_target(const Vpl& v) {
  return v.kind == VplKind::Surface || v.kind == VplKind::Area ? offset_point(v.position, v.normal) : v.position;
}

struct ShadowQuery {
  glm::vec3 origin, direction;
  float tfar = 0.0f;
};

struct VplShading {
  const Scene& scene;
  float clamp_bound;  // bound on G = cos_x cos_y / r^2; infinity when off
  // GGX VPLs radiate through a lobe at least this rough (the glossy
  // threshold, methods/glossy_gather.h): see vpl_bsdf().
  float min_emitter_alpha = 0.0f;
  // Receivers whose GGX lobe is sharper than this gather that lobe with rays
  // (ir, igi: the glossy threshold), so VPLs light only the rest of them
  // (material/bsdf.h: vpl_lobes); 0: VPLs light every lobe (lightcuts, and
  // the exact lights, whose light no gather ray can find).
  float gathered_below = 0.0f;

  // The receiver's BSDF divided by modulation(): bsdf_eval's rule, the path
  // tracer's, for every material (light and viewer on the geometric side and
  // above the shading normal; shadow_batch's fast lanes test the same), over
  // the lobes VPL light reaches.
  glm::vec3 receiver_bsdf(const SurfacePoint& sp, glm::vec3 wo, glm::vec3 wi) const {
    return demodulated_bsdf(sp, wo, wi, vpl_lobes(sp, gathered_below));
  }

  // BSDF at a surface VPL, light arriving from v.incident and leaving along
  // `out`. A VPL on a sharp GGX surface radiates through its lobe widened to
  // min_emitter_alpha: at alpha 0.04 the lobe peaks at D = 1 / (pi alpha^2)
  // = 199 and each VPL would cast a spot of its own; widened to 0.2 (D = 8)
  // the spots merge into the smooth light such a surface reflects onto a
  // room. The lobe keeps its direction and (nearly) its albedo: the light is
  // blurred, not lost (the glossy scene's mean is within 1 % of pt).
  glm::vec3 vpl_bsdf(const Vpl& v, glm::vec3 out) const { return vpl_bsdf(v, out, v.albedo); }
  // The same lobe with another albedo (1: what the clamp bounds).
  glm::vec3 vpl_bsdf(const Vpl& v, glm::vec3 out, glm::vec3 albedo) const {
    const Material& m = scene.materials[v.material];
    if (m.type == MaterialType::Diffuse) return albedo * kInvPi;
    if (m.type == MaterialType::MetallicRoughness) {
      const MetallicRoughnessPoint p{albedo, v.metallic, std::max(v.alpha, min_emitter_alpha), m.specular_f0,
                                     m.specular_weight};
      const Onb frame(v.normal);
      return metallic_roughness_eval(p, frame.to_local(v.incident), frame.to_local(out),
                                     v.diffuse_only ? Lobes::Diffuse : Lobes::All);
    }
    return ggx_reflection(v.normal, v.incident, out, albedo, std::max(m.alpha, min_emitter_alpha));
  }
  // Whether a lobe at either end is clamped as glossy (core/clamp.h).
  static bool glossy(const Material& m) {
    return m.type == MaterialType::Conductor || m.type == MaterialType::MetallicRoughness;
  }

  // Returns the contribution at `sp`, seen from `wo` (zero when none), and fills the shadow ray.
  glm::vec3 contribution(const GSample& g, const Vpl& v, ShadowQuery& q) const {
    return contribution(g.surface, g.wo, v, q);
  }
  glm::vec3 contribution(const SurfacePoint& sp, glm::vec3 wo, const Vpl& v, ShadowQuery& q) const {
    glm::vec3 wi, emitted;
    float g_term, distance;
    if (v.kind == VplKind::Directional) {
      wi = -v.normal;
      distance = INFINITY;
      g_term = std::abs(glm::dot(wi, sp.shading_normal));
      emitted = v.flux;
    } else {
      glm::vec3 d = v.position - sp.position;
      float dist2 = glm::dot(d, d);
      distance = std::sqrt(dist2);
      wi = d / distance;
      float cos_x = std::abs(glm::dot(wi, sp.shading_normal));
      if (v.kind == VplKind::Surface || v.kind == VplKind::Area) {
        float cos_y = -glm::dot(wi, v.normal);
        if (cos_y <= 0.0f) return glm::vec3(0.0f);
        g_term = std::min(cos_x * cos_y / dist2, clamp_bound);
        emitted = v.kind == VplKind::Surface ? vpl_bsdf(v, -wi) * v.flux : v.flux;
        // The clamp at the emitting end as at the receiving one (clamp.h): a
        // GGX VPL's lobe times G is bounded by what a white Lambertian VPL
        // gives at most. On `glossy` the floor's VPLs lit the walls' feet
        // with spots at their lobes' peaks; on `courtyard`, the metal ball's
        // lit the ground (tests/bench/history/RESULTS-to-2026-12-05.md, "Glossy VPLs clamped").
        if (v.kind == VplKind::Surface && glossy(scene.materials[v.material]))
          emitted *= glossy_lobe_clamp(max_component(vpl_bsdf(v, -wi, glm::vec3(1.0f))), g_term, clamp_bound);
      } else {
        g_term = cos_x / dist2;  // exact point and spot lights: never clamped
        emitted = v.kind == VplKind::Spot ? v.flux * spot_attenuation(scene.lights[v.light], -wi) : v.flux;
      }
    }
    glm::vec3 f = receiver_bsdf(sp, wo, wi);
    const bool clamped = v.kind == VplKind::Surface || v.kind == VplKind::Area;
    if (clamped && glossy(*sp.material))
      f *= glossy_lobe_clamp(max_component(f), g_term, clamp_bound);
    glm::vec3 c = f * emitted * g_term;
    // Nothing, or a VPL on the point itself (unclamped: infinite or NaN).
    if (!(c.x + c.y + c.z > 0.0f) || !std::isfinite(c.x + c.y + c.z)) return glm::vec3(0.0f);
    const Ray ray = shadow_ray(sp, wi, shadow_target(v), distance);
    q = ShadowQuery{ray.origin, ray.direction, ray.tfar};
    return c;
  }
};

}  // namespace igi
