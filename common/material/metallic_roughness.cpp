#include "material/metallic_roughness.h"

#include <algorithm>
#include <cmath>

#include "material/ggx.h"
#include "sampling/warp.h"

namespace igi {
namespace {

float mean(glm::vec3 c) { return (c.x + c.y + c.z) * (1.0f / 3.0f); }

// The Fresnel terms at Schlick weight s = (1 - cos)^5, and the weights of
// the two lobes: the diffuse base's (1 - metallic) (1 - w max(F_d)) and the
// GGX lobe's (1 - metallic) w F_d + metallic F_m.
struct LobeWeights {
  float diffuse = 0.0f;
  glm::vec3 specular{0.0f};
};

LobeWeights lobe_weights(const MetallicRoughnessPoint& p, float s) {
  const glm::vec3 dielectric = p.f0 + (glm::vec3(1.0f) - p.f0) * s;
  const glm::vec3 metal = p.base + (glm::vec3(1.0f) - p.base) * s;
  LobeWeights w;
  w.diffuse = (1.0f - p.metallic) * (1.0f - p.weight * max_component(dielectric));
  w.specular = (1.0f - p.metallic) * p.weight * dielectric + p.metallic * metal;
  return w;
}

}  // namespace

glm::vec3 metallic_roughness_eval(const MetallicRoughnessPoint& p, glm::vec3 lo, glm::vec3 li, Lobes lobes) {
  if (lo.z <= 0.0f || li.z <= 0.0f) return glm::vec3(0.0f);
  const glm::vec3 h = glm::normalize(lo + li);
  const LobeWeights w = lobe_weights(p, schlick_weight(glm::dot(lo, h)));
  glm::vec3 f(0.0f);
  if (has_lobe(lobes, Lobes::Diffuse)) f += (w.diffuse * kInvPi) * p.base;
  if (has_lobe(lobes, Lobes::Specular)) f += w.specular * ggx_lobe(lo, li, h, p.alpha);
  return f;
}

float metallic_roughness_specular_probability(const MetallicRoughnessPoint& p, float cos_o) {
  const LobeWeights w = lobe_weights(p, schlick_weight(cos_o));
  const float diffuse = w.diffuse * mean(p.base), specular = mean(w.specular);
  if (!(diffuse > 0.0f)) return 1.0f;
  if (!(specular > 0.0f)) return 0.0f;
  return std::clamp(specular / (specular + diffuse), 0.1f, 0.9f);
}

float metallic_roughness_pdf(const MetallicRoughnessPoint& p, glm::vec3 lo, glm::vec3 li, Lobes lobes) {
  if (lo.z <= 0.0f || li.z <= 0.0f) return 0.0f;
  const float diffuse = li.z * kInvPi;
  if (lobes == Lobes::Diffuse) return diffuse;
  const float specular = ggx_reflection_pdf(lo, li, p.alpha);
  if (lobes == Lobes::Specular) return specular;
  const float q = metallic_roughness_specular_probability(p, lo.z);
  return q * specular + (1.0f - q) * diffuse;
}

glm::vec3 metallic_roughness_sample(const MetallicRoughnessPoint& p, glm::vec3 lo, glm::vec2 u, float u_lobe,
                                    Lobes lobes, bool& specular) {
  specular = lobes == Lobes::Specular ||
             (lobes == Lobes::All && u_lobe < metallic_roughness_specular_probability(p, lo.z));
  if (!specular) return cosine_hemisphere(u);
  return reflect(lo, ggx_sample_visible_normal(lo, p.alpha, u));
}

glm::vec3 metallic_roughness_albedo(const MetallicRoughnessPoint& p, float cos_o) {
  const float s = schlick_weight(cos_o);
  const LobeWeights w = lobe_weights(p, s);
  return glm::max(w.diffuse * p.base + w.specular, glm::vec3(kMinModulation));
}

}  // namespace igi
