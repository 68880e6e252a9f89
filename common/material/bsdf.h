#pragma once
// The five material models, evaluated and sampled in world space: Lambert,
// the GGX conductor, mirror, glass and glTF's metallic-roughness BRDF
// (material/metallic_roughness.h).
//
// Conventions: wo and wi are unit vectors pointing away from the surface;
// eval() returns the BSDF value f(wo, wi) without the cosine; sample()
// returns weight = f * |cos(wi, n)| / pdf. Specular lobes (mirror, glass)
// are Dirac deltas: eval() and pdf() return 0 for them and sample() marks its
// result specular. Both sides of a surface reflect alike (the shading normal
// is flipped towards wo); single-sidedness is decided by ray tracing.
// `lobes` restricts a call to some lobes (metallic_roughness.h: Lobes); a
// one-lobe model outside them evaluates to 0 and samples nothing.
#include <cmath>
#include <optional>

#include <glm/glm.hpp>

#include "material/metallic_roughness.h"
#include "scene/surface.h"

namespace igi {

struct BsdfSample {
  glm::vec3 wi;
  glm::vec3 weight;  // f * |cos| / pdf
  float pdf = 0.0f;  // solid angle; undefined (set to 1) for specular
  bool specular = false;
  // How sharp the lobe it came from: the GGX alpha of a glossy lobe,
  // infinity for a diffuse one, 0 for mirrors and glass (specular).
  float lobe_alpha = INFINITY;
};

glm::vec3 bsdf_eval(const SurfacePoint& sp, glm::vec3 wo, glm::vec3 wi, Lobes lobes = Lobes::All);
float bsdf_pdf(const SurfacePoint& sp, glm::vec3 wo, glm::vec3 wi, Lobes lobes = Lobes::All);
// u: 2D sample for the direction; u_lobe: 1D sample for choosing a lobe (glass, metallic-roughness).
std::optional<BsdfSample> bsdf_sample(const SurfacePoint& sp, glm::vec3 wo, glm::vec2 u, float u_lobe,
                                      Lobes lobes = Lobes::All);

// The metallic-roughness model's values at sp.
MetallicRoughnessPoint metallic_roughness_point(const SurfacePoint& sp);

// What the VPL methods demodulate by: they sum light times the BSDF divided
// by this, filter those sums over neighbouring pixels (igi), and multiply
// the result by it once (core/vpl_contribution.h). The albedo (base colour
// times texture) for Lambert, the conductor, mirrors and glass, so their
// BSDF "with albedo 1" is the demodulated one; for the metallic-roughness
// model an estimate of its directional albedo towards wo (its lobes are
// coloured differently: the base, the coat's F0 and the metal's Schlick), so
// that on a textured surface the filter averages light, not texture.
glm::vec3 modulation(const SurfacePoint& sp, glm::vec3 wo);
// The BSDF divided by modulation(sp, wo), and a sample of it (weight f cos
// / pdf / modulation).
glm::vec3 demodulated_bsdf(const SurfacePoint& sp, glm::vec3 wo, glm::vec3 wi, Lobes lobes = Lobes::All);
std::optional<BsdfSample> demodulated_sample(const SurfacePoint& sp, glm::vec3 wo, glm::vec2 u, float u_lobe,
                                             Lobes lobes = Lobes::All);

// The GGX conductor lobe for a surface of unit normal n (either side: it is
// turned towards wo), Fresnel f0, roughness alpha; zero unless wo and wi are
// both on n's side. bsdf_eval's Conductor case.
glm::vec3 ggx_reflection(glm::vec3 n, glm::vec3 wo, glm::vec3 wi, glm::vec3 f0, float alpha);

// Fresnel reflectance of a smooth dielectric; cos_i may be negative (inside).
float fresnel_dielectric(float cos_i, float eta);

// Both branches of smooth glass seen from wo, on either side: the mirror
// direction with the exact Fresnel reflectance F, and the refracted direction
// with weight (1 - F) x tint. Under total internal reflection F = 1 and there
// is no refracted branch. bsdf_sample picks one with probability F (weight 1
// or tint); following both with these weights gives the same mean, noiselessly.
struct DielectricBranches {
  glm::vec3 reflected{0.0f};
  float reflectance = 1.0f;          // F
  glm::vec3 refracted{0.0f};         // valid when reflectance < 1
  glm::vec3 transmittance{0.0f};     // (1 - F) x tint
};
DielectricBranches dielectric_branches(const SurfacePoint& sp, glm::vec3 wo);

// How the VPL methods treat a surface (RenderSettings::glossy_threshold): a
// GGX lobe sharper than the threshold is gathered with BSDF-sampled rays
// (methods/glossy_gather.h), and VPL light reaches the rest (vpl_lobes): a
// Lambertian or rougher GGX surface whole, the diffuse base of a
// metallic-roughness surface with a sharp coat or metal, and nothing of a
// sharp conductor, a mirror or glass.
inline bool is_gathered_glossy(const SurfacePoint& sp, float glossy_threshold) {
  const MaterialType type = sp.material->type;
  if (type == MaterialType::MetallicRoughness) return sp.alpha < glossy_threshold;
  return type == MaterialType::Conductor && sp.material->alpha < glossy_threshold;
}
inline Lobes vpl_lobes(const SurfacePoint& sp, float glossy_threshold) {
  if (sp.material->type == MaterialType::MetallicRoughness)
    return sp.alpha < glossy_threshold ? Lobes::Diffuse : Lobes::All;
  return Lobes::All;
}
inline bool receives_vpls(const SurfacePoint& sp, float glossy_threshold) {
  if (sp.material->type == MaterialType::MetallicRoughness) return sp.alpha >= glossy_threshold || sp.metallic < 1.0f;
  return !sp.material->is_specular() && !is_gathered_glossy(sp, glossy_threshold);
}

// With caustics on, what focuses light: mirrors, glass and GGX lobes sharper
// than a quarter of the glossy threshold (focus_alpha). Light paths leave no
// VPL where a surface has nothing else (a metallic-roughness surface with so
// sharp a coat keeps a VPL that radiates through its diffuse base alone) and
// carry the light on; photon paths count a bounce through such a lobe as
// specular (`focused`), so its light reaches diffuse surfaces as caustic
// photons. A VPL on such a lobe lit its neighbours through a lobe widened to
// the threshold: a few bright squares on the ground beside the courtyard's
// metal ball (alpha 0.02), dark streaks at the foot of the glossy scene's
// walls (0.04), and an image that converged to the widened lobe (glossy at 64
// passes: FLIP 0.069 by VPLs, 0.048 by photons;
// tests/bench/history/RESULTS-to-2026-12-05.md, "Sharp glossy light as
// caustics"). Lobes between a quarter of the threshold and the threshold
// (the glossy coats of paint and plastic that glTF files are full of,
// roughness 0.22 to 0.45) are gathered from the camera but light the scene
// through VPLs, their lobe widened to the threshold at most 4 times: as
// photons, the light a glossy white wall reflects onto the next speckled it
// in bright blotches that 16 passes did not smooth (BreakfastRoom).
inline float focus_alpha(float glossy_threshold) { return 0.25f * glossy_threshold; }
inline bool focuses_light(const SurfacePoint& sp, float glossy_threshold) {
  const Material& m = *sp.material;
  if (m.type == MaterialType::MetallicRoughness) return sp.metallic >= 1.0f && sp.alpha < focus_alpha(glossy_threshold);
  return m.is_specular() || (m.type == MaterialType::Conductor && m.alpha < focus_alpha(glossy_threshold));
}
inline bool focused(const BsdfSample& s, float glossy_threshold) {
  return s.specular || s.lobe_alpha < focus_alpha(glossy_threshold);
}
// Whether some point of a surface of material m focuses light, or has a lobe that does.
inline bool may_focus_light(const Material& m, float glossy_threshold) {
  if (m.type == MaterialType::MetallicRoughness) return m.min_alpha < focus_alpha(glossy_threshold);
  return m.is_specular() || (m.type == MaterialType::Conductor && m.alpha < focus_alpha(glossy_threshold));
}
// The lobes a VPL on sp radiates through with caustics on: all but a focusing one.
inline Lobes radiating_lobes(const SurfacePoint& sp, float glossy_threshold) {
  const bool sharp = sp.material->type == MaterialType::MetallicRoughness && sp.alpha < focus_alpha(glossy_threshold);
  return sharp ? Lobes::Diffuse : Lobes::All;
}

}  // namespace igi
