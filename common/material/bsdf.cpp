#include "material/bsdf.h"

#include <cmath>

#include "sampling/warp.h"

namespace igi {
namespace {

// Both directions on the same side of the geometric surface: reflection.
bool same_hemisphere(const SurfacePoint& sp, glm::vec3 wo, glm::vec3 wi) {
  return glm::dot(wo, sp.geometric_normal) * glm::dot(wi, sp.geometric_normal) > 0.0f;
}

// --- GGX (Trowbridge-Reitz) in the local frame, z = normal ---
float ggx_d(glm::vec3 h, float alpha) {
  float a2 = alpha * alpha;
  float c2 = h.z * h.z;
  float denom = c2 * (a2 - 1.0f) + 1.0f;
  return a2 / (kPi * denom * denom);
}

float ggx_lambda(glm::vec3 w, float alpha) {
  float c2 = w.z * w.z;
  if (c2 <= 0.0f) return 0.0f;
  float tan2 = std::max(0.0f, 1.0f - c2) / c2;
  return 0.5f * (std::sqrt(1.0f + alpha * alpha * tan2) - 1.0f);
}

float ggx_g1(glm::vec3 w, float alpha) { return 1.0f / (1.0f + ggx_lambda(w, alpha)); }
float ggx_g2(glm::vec3 wo, glm::vec3 wi, float alpha) {
  return 1.0f / (1.0f + ggx_lambda(wo, alpha) + ggx_lambda(wi, alpha));
}

// Visible-normal sampling (Heitz 2018), wo in the upper hemisphere.
glm::vec3 ggx_sample_visible_normal(glm::vec3 wo, float alpha, glm::vec2 u) {
  glm::vec3 vh = glm::normalize(glm::vec3(alpha * wo.x, alpha * wo.y, wo.z));
  float len2 = vh.x * vh.x + vh.y * vh.y;
  glm::vec3 t1 = len2 > 0.0f ? glm::vec3(-vh.y, vh.x, 0.0f) / std::sqrt(len2) : glm::vec3(1, 0, 0);
  glm::vec3 t2 = glm::cross(vh, t1);
  float r = std::sqrt(u.x), phi = 2.0f * kPi * u.y;
  float p1 = r * std::cos(phi), p2 = r * std::sin(phi);
  float s = 0.5f * (1.0f + vh.z);
  p2 = (1.0f - s) * std::sqrt(std::max(0.0f, 1.0f - p1 * p1)) + s * p2;
  glm::vec3 nh = p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0f, 1.0f - p1 * p1 - p2 * p2)) * vh;
  return glm::normalize(glm::vec3(alpha * nh.x, alpha * nh.y, std::max(1e-6f, nh.z)));
}

float conductor_pdf_local(glm::vec3 wo, glm::vec3 wi, float alpha) {
  if (wo.z <= 0.0f || wi.z <= 0.0f) return 0.0f;
  glm::vec3 h = glm::normalize(wo + wi);
  return ggx_g1(wo, alpha) * ggx_d(h, alpha) / (4.0f * wo.z);
}

glm::vec3 conductor_eval_local(glm::vec3 wo, glm::vec3 wi, glm::vec3 f0, float alpha) {
  if (wo.z <= 0.0f || wi.z <= 0.0f) return glm::vec3(0.0f);
  glm::vec3 h = glm::normalize(wo + wi);
  return f0 * (ggx_d(h, alpha) * ggx_g2(wo, wi, alpha) / (4.0f * wo.z * wi.z));
}

glm::vec3 reflect(glm::vec3 wo, glm::vec3 n) { return 2.0f * glm::dot(wo, n) * n - wo; }

std::optional<BsdfSample> sample_glass(const SurfacePoint& sp, glm::vec3 wo, float u_lobe) {
  const DielectricBranches b = dielectric_branches(sp, wo);
  if (u_lobe < b.reflectance) return BsdfSample{b.reflected, glm::vec3(1.0f), 1.0f, true};
  return BsdfSample{b.refracted, sp.albedo, 1.0f, true};
}

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

glm::vec3 bsdf_eval(const SurfacePoint& sp, glm::vec3 wo, glm::vec3 wi) {
  if (sp.material->is_specular() || !same_hemisphere(sp, wo, wi)) return glm::vec3(0.0f);
  Onb frame(sp.shading_normal_facing(wo));
  glm::vec3 lo = frame.to_local(wo), li = frame.to_local(wi);
  if (sp.material->type == MaterialType::Diffuse)
    return li.z > 0.0f && lo.z > 0.0f ? sp.albedo * kInvPi : glm::vec3(0.0f);
  return conductor_eval_local(lo, li, sp.albedo, sp.material->alpha);
}

float bsdf_pdf(const SurfacePoint& sp, glm::vec3 wo, glm::vec3 wi) {
  if (sp.material->is_specular() || !same_hemisphere(sp, wo, wi)) return 0.0f;
  Onb frame(sp.shading_normal_facing(wo));
  glm::vec3 lo = frame.to_local(wo), li = frame.to_local(wi);
  if (sp.material->type == MaterialType::Diffuse) return li.z > 0.0f ? li.z * kInvPi : 0.0f;
  return conductor_pdf_local(lo, li, sp.material->alpha);
}

std::optional<BsdfSample> bsdf_sample(const SurfacePoint& sp, glm::vec3 wo, glm::vec2 u, float u_lobe) {
  const Material& m = *sp.material;
  if (m.type == MaterialType::Glass) return sample_glass(sp, wo, u_lobe);
  Onb frame(sp.shading_normal_facing(wo));
  if (m.type == MaterialType::Mirror)
    return BsdfSample{reflect(wo, frame.n), sp.albedo, 1.0f, true};
  glm::vec3 lo = frame.to_local(wo);
  if (lo.z <= 0.0f) return std::nullopt;
  glm::vec3 li;
  if (m.type == MaterialType::Diffuse) {
    li = cosine_hemisphere(u);
  } else {
    glm::vec3 h = ggx_sample_visible_normal(lo, m.alpha, u);
    li = reflect(lo, h);
  }
  glm::vec3 wi = frame.to_world(li);
  if (li.z <= 0.0f || !same_hemisphere(sp, wo, wi)) return std::nullopt;
  float pdf = bsdf_pdf(sp, wo, wi);
  if (!(pdf > 0.0f)) return std::nullopt;
  return BsdfSample{wi, bsdf_eval(sp, wo, wi) * li.z / pdf, pdf, false};
}

}  // namespace igi
