#pragma once
// The four material models, evaluated and sampled in world space.
//
// Conventions: wo and wi are unit vectors pointing away from the surface;
// eval() returns the BSDF value f(wo, wi) without the cosine; sample()
// returns weight = f * |cos(wi, n)| / pdf. Specular lobes (mirror, glass)
// are Dirac deltas: eval() and pdf() return 0 for them and sample() marks its
// result specular. Both sides of a surface reflect alike (the shading normal
// is flipped towards wo); single-sidedness is decided by ray tracing.
#include <optional>

#include <glm/glm.hpp>

#include "scene/surface.h"

namespace igi {

struct BsdfSample {
  glm::vec3 wi;
  glm::vec3 weight;  // f * |cos| / pdf
  float pdf = 0.0f;  // solid angle; undefined (set to 1) for specular
  bool specular = false;
};

glm::vec3 bsdf_eval(const SurfacePoint& sp, glm::vec3 wo, glm::vec3 wi);
float bsdf_pdf(const SurfacePoint& sp, glm::vec3 wo, glm::vec3 wi);
// u: 2D sample for the direction; u_lobe: 1D sample for choosing a lobe (glass).
std::optional<BsdfSample> bsdf_sample(const SurfacePoint& sp, glm::vec3 wo, glm::vec2 u, float u_lobe);

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

// How the VPL methods treat a material (RenderSettings::glossy_threshold):
// a GGX lobe sharper than the threshold is gathered with BSDF-sampled rays;
// VPLs neither sit on nor shade it, nor mirrors and glass.
inline bool is_gathered_glossy(const Material& m, float glossy_threshold) {
  return m.type == MaterialType::Conductor && m.alpha < glossy_threshold;
}
inline bool receives_vpls(const Material& m, float glossy_threshold) {
  return !m.is_specular() && !is_gathered_glossy(m, glossy_threshold);
}

// With caustics on, what focuses light: mirrors, glass and the GGX lobes the
// camera side gathers (sharper than the glossy threshold). Light paths leave
// no VPL there and carry the light on; photon paths count them as specular,
// so their light reaches diffuse surfaces as caustic photons. A VPL on such a
// lobe lit its neighbours through a lobe widened to the threshold: a few
// bright squares on the ground beside the courtyard's metal ball, dark
// streaks at the foot of the glossy scene's walls, and an image that
// converged to the widened lobe (glossy at 64 passes: FLIP 0.069 by VPLs,
// 0.048 by photons; tests/bench/history/RESULTS-to-2026-12-05.md, "Sharp glossy light as caustics").
inline bool focuses_light(const Material& m, float glossy_threshold) {
  return m.is_specular() || is_gathered_glossy(m, glossy_threshold);
}

}  // namespace igi
