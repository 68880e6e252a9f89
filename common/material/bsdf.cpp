#include "material/bsdf.h"

#include <cmath>

#include "material/ggx.h"
#include "sampling/warp.h"

namespace igi {
namespace {

// Both directions on the same side of the geometric surface: reflection.
bool same_hemisphere(const SurfacePoint& sp, glm::vec3 wo, glm::vec3 wi) {
  return glm::dot(wo, sp.geometric_normal) * glm::dot(wi, sp.geometric_normal) > 0.0f;
}

glm::vec3 conductor_eval_local(glm::vec3 wo, glm::vec3 wi, glm::vec3 f0, float alpha) {
  if (wo.z <= 0.0f || wi.z <= 0.0f) return glm::vec3(0.0f);
  glm::vec3 h = glm::normalize(wo + wi);
  return f0 * ggx_lobe(wo, wi, h, alpha);
}

std::optional<BsdfSample> sample_glass(const SurfacePoint& sp, glm::vec3 wo, float u_lobe) {
  const DielectricBranches b = dielectric_branches(sp, wo);
  if (u_lobe < b.reflectance) return BsdfSample{b.reflected, glm::vec3(1.0f), 1.0f, true, 0.0f};
  return BsdfSample{b.refracted, sp.albedo, 1.0f, true, 0.0f};
}

// A mirror tinted by its base colour, or by glTF's metal Fresnel: Schlick
// from F0 = base colour at normal incidence to 1 at grazing.
std::optional<BsdfSample> sample_mirror(const SurfacePoint& sp, glm::vec3 n, glm::vec3 wo) {
  glm::vec3 tint = sp.albedo;
  if (sp.material->schlick_fresnel) tint += (glm::vec3(1.0f) - tint) * schlick_weight(std::abs(glm::dot(wo, n)));
  return BsdfSample{reflect(wo, n), tint, 1.0f, true, 0.0f};
}

// The lobe a one-lobe model has.
Lobes only_lobe(MaterialType type) { return type == MaterialType::Diffuse ? Lobes::Diffuse : Lobes::Specular; }

}  // namespace

float fresnel_dielectric(float cos_i, float eta) {
  if (cos_i < 0.0f) { eta = 1.0f / eta; cos_i = -cos_i; }
  float sin2_t = std::max(0.0f, 1.0f - cos_i * cos_i) / (eta * eta);
  if (sin2_t >= 1.0f) return 1.0f;  // total internal reflection
  float cos_t = std::sqrt(1.0f - sin2_t);
  float r_parl = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  float r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  return 0.5f * (r_parl * r_parl + r_perp * r_perp);
}

DielectricBranches dielectric_branches(const SurfacePoint& sp, glm::vec3 wo) {
  glm::vec3 n = sp.shading_normal;
  float cos_o = glm::dot(wo, n);
  const bool entering = glm::dot(wo, sp.geometric_normal) > 0.0f;
  const float eta = entering ? sp.material->ior : 1.0f / sp.material->ior;  // eta_t / eta_i
  if (!entering) { n = -n; cos_o = -cos_o; }
  DielectricBranches b;
  b.reflected = reflect(wo, n);
  b.reflectance = fresnel_dielectric(cos_o, eta);
  if (b.reflectance >= 1.0f) return b;
  const float sin2_t = std::max(0.0f, 1.0f - cos_o * cos_o) / (eta * eta);
  const float cos_t = std::sqrt(std::max(0.0f, 1.0f - sin2_t));
  b.refracted = glm::normalize(-wo / eta + (cos_o / eta - cos_t) * n);
  b.transmittance = (1.0f - b.reflectance) * sp.albedo;
  return b;
}

glm::vec3 ggx_reflection(glm::vec3 n, glm::vec3 wo, glm::vec3 wi, glm::vec3 f0, float alpha) {
  const Onb frame(glm::dot(wo, n) >= 0.0f ? n : -n);
  return conductor_eval_local(frame.to_local(wo), frame.to_local(wi), f0, alpha);
}

MetallicRoughnessPoint metallic_roughness_point(const SurfacePoint& sp) {
  return {sp.albedo, sp.metallic, sp.alpha, sp.material->specular_f0, sp.material->specular_weight};
}

glm::vec3 bsdf_eval(const SurfacePoint& sp, glm::vec3 wo, glm::vec3 wi, Lobes lobes) {
  if (sp.material->is_specular() || !same_hemisphere(sp, wo, wi)) return glm::vec3(0.0f);
  Onb frame(sp.shading_normal_facing(wo));
  glm::vec3 lo = frame.to_local(wo), li = frame.to_local(wi);
  const MaterialType type = sp.material->type;
  if (type == MaterialType::MetallicRoughness) return metallic_roughness_eval(metallic_roughness_point(sp), lo, li, lobes);
  if (!has_lobe(lobes, only_lobe(type))) return glm::vec3(0.0f);
  if (type == MaterialType::Diffuse)
    return li.z > 0.0f && lo.z > 0.0f ? sp.albedo * kInvPi : glm::vec3(0.0f);
  return conductor_eval_local(lo, li, sp.albedo, sp.material->alpha);
}

float bsdf_pdf(const SurfacePoint& sp, glm::vec3 wo, glm::vec3 wi, Lobes lobes) {
  if (sp.material->is_specular() || !same_hemisphere(sp, wo, wi)) return 0.0f;
  Onb frame(sp.shading_normal_facing(wo));
  glm::vec3 lo = frame.to_local(wo), li = frame.to_local(wi);
  const MaterialType type = sp.material->type;
  if (type == MaterialType::MetallicRoughness) return metallic_roughness_pdf(metallic_roughness_point(sp), lo, li, lobes);
  if (!has_lobe(lobes, only_lobe(type))) return 0.0f;
  if (type == MaterialType::Diffuse) return li.z > 0.0f ? li.z * kInvPi : 0.0f;
  return ggx_reflection_pdf(lo, li, sp.material->alpha);
}

std::optional<BsdfSample> bsdf_sample(const SurfacePoint& sp, glm::vec3 wo, glm::vec2 u, float u_lobe, Lobes lobes) {
  const Material& m = *sp.material;
  if (m.type != MaterialType::MetallicRoughness && !has_lobe(lobes, only_lobe(m.type))) return std::nullopt;
  if (m.type == MaterialType::Glass) return sample_glass(sp, wo, u_lobe);
  Onb frame(sp.shading_normal_facing(wo));
  if (m.type == MaterialType::Mirror) return sample_mirror(sp, frame.n, wo);
  glm::vec3 lo = frame.to_local(wo);
  if (lo.z <= 0.0f) return std::nullopt;
  glm::vec3 li;
  bool glossy = m.type == MaterialType::Conductor;
  if (m.type == MaterialType::MetallicRoughness) {
    li = metallic_roughness_sample(metallic_roughness_point(sp), lo, u, u_lobe, lobes, glossy);
  } else if (m.type == MaterialType::Diffuse) {
    li = cosine_hemisphere(u);
  } else {
    glm::vec3 h = ggx_sample_visible_normal(lo, m.alpha, u);
    li = reflect(lo, h);
  }
  glm::vec3 wi = frame.to_world(li);
  if (li.z <= 0.0f || !same_hemisphere(sp, wo, wi)) return std::nullopt;
  float pdf = bsdf_pdf(sp, wo, wi, lobes);
  if (!(pdf > 0.0f)) return std::nullopt;
  const float lobe_alpha = m.type == MaterialType::MetallicRoughness ? sp.alpha : m.alpha;
  return BsdfSample{wi, bsdf_eval(sp, wo, wi, lobes) * li.z / pdf, pdf, false, glossy ? lobe_alpha : INFINITY};
}

glm::vec3 modulation(const SurfacePoint& sp, glm::vec3 wo) {
  if (sp.material->type != MaterialType::MetallicRoughness) return sp.albedo;
  return metallic_roughness_albedo(metallic_roughness_point(sp), std::max(0.0f, glm::dot(wo, sp.shading_normal_facing(wo))));
}

glm::vec3 demodulated_bsdf(const SurfacePoint& sp, glm::vec3 wo, glm::vec3 wi, Lobes lobes) {
  if (sp.material->type == MaterialType::MetallicRoughness) return bsdf_eval(sp, wo, wi, lobes) / modulation(sp, wo);
  SurfacePoint white = sp;
  white.albedo = glm::vec3(1.0f);
  return bsdf_eval(white, wo, wi, lobes);
}

std::optional<BsdfSample> demodulated_sample(const SurfacePoint& sp, glm::vec3 wo, glm::vec2 u, float u_lobe,
                                             Lobes lobes) {
  if (sp.material->type == MaterialType::MetallicRoughness) {
    std::optional<BsdfSample> s = bsdf_sample(sp, wo, u, u_lobe, lobes);
    if (s) s->weight /= modulation(sp, wo);
    return s;
  }
  SurfacePoint white = sp;
  white.albedo = glm::vec3(1.0f);
  return bsdf_sample(white, wo, u, u_lobe, lobes);
}

}  // namespace igi
