#pragma once
// glTF 2.0's metallic-roughness BRDF, as the specification's Appendix B
// defines it, with KHR_materials_specular and KHR_materials_ior:
//
//   f = (1 - metallic) dielectric + metallic metal
//   dielectric = (1 - w max(F_d)) base / pi + w F_d D V      (fresnel_mix)
//   metal      = F_m D V
//   F_d = f0 + (1 - f0) (1 - |v.h|)^5,  F_m = base + (1 - base) (1 - |v.h|)^5
//
// D: GGX with alpha = roughness^2; V = G2 / (4 |n.l| |n.v|), G2 the
// height-correlated Smith term (material/ggx.h); f0 = min(((ior - 1) /
// (ior + 1))^2 specularColor, 1), 0.04 for the core material; w the
// specularFactor (1). It is reciprocal (|v.h| = |l.h|), and the diffuse
// lobe is Lambert's (not Burley's, as Blender 3's Principled has).
//
// What the Fresnel weighting with |v.h| does to energy: at normal and
// moderate incidence a white dielectric reflects at most 1, but the diffuse
// base is dimmed by the half vector's Fresnel, not the view's, so at
// grazing views the coat's reflection adds to a nearly undimmed base: a
// white smooth dielectric seen at 86 degrees reflects 1.55 of what arrives
// (roughness 0.55: 1.10). That is the specification's model, and what every
// renderer of it draws (tests/common/material/test_metallic_roughness.cpp measures it).
//
// Two lobes, sampled by one choice: the diffuse one (cosine) and the GGX one
// (visible normals, shared by the coat and the metal), picked with the
// probability of an estimate of the GGX lobe's share of the reflected light
// at the view angle (kept within [0.1, 0.9] where both lobes reflect), the
// pdf being the mixture of both (one-sample MIS, balance heuristic).
// Functions take directions in the local frame (z = the shading normal
// turned to the viewer) and need lo.z > 0 and li.z > 0 for a non-zero value.
#include <cstdint>

#include <glm/glm.hpp>

namespace igi {

// Which lobes of a BSDF a call means. The metallic-roughness model has two;
// the other models one, Diffuse for Lambert, Specular for the rest.
enum class Lobes : uint8_t { Diffuse = 1, Specular = 2, All = 3 };
inline bool has_lobe(Lobes set, Lobes lobe) { return (uint8_t(set) & uint8_t(lobe)) != 0; }

// The model's values at one surface point.
struct MetallicRoughnessPoint {
  glm::vec3 base{0.0f};   // base colour, textured
  float metallic = 0.0f;
  float alpha = 1.0f;
  glm::vec3 f0{0.04f};    // the dielectric coat's F0
  float weight = 1.0f;    // KHR_materials_specular's specularFactor
};

glm::vec3 metallic_roughness_eval(const MetallicRoughnessPoint& p, glm::vec3 lo, glm::vec3 li, Lobes lobes);
float metallic_roughness_pdf(const MetallicRoughnessPoint& p, glm::vec3 lo, glm::vec3 li, Lobes lobes);

// A direction from the lobes (u_lobe picks one of two); specular: it came
// from the GGX lobe. Below the surface (li.z <= 0) when the sample fails.
glm::vec3 metallic_roughness_sample(const MetallicRoughnessPoint& p, glm::vec3 lo, glm::vec2 u, float u_lobe,
                                    Lobes lobes, bool& specular);

// The probability of choosing the GGX lobe at a view of cos_o.
float metallic_roughness_specular_probability(const MetallicRoughnessPoint& p, float cos_o);

// An estimate of the light the whole BRDF reflects towards a view of cos_o
// (its directional albedo, per channel), with Fresnel taken at n.v and the
// GGX lobe counted whole: what the VPL methods demodulate by (material/bsdf.h:
// modulation). At least kMinModulation in every channel.
inline constexpr float kMinModulation = 1e-3f;
glm::vec3 metallic_roughness_albedo(const MetallicRoughnessPoint& p, float cos_o);

}  // namespace igi
