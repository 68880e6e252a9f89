#include "lightcuts/light_leaves.h"

#include <cmath>

#include "lightcuts/bounds.h"
#include "sampling/warp.h"

namespace igi::lightcuts {
namespace {

// A Surface or Area VPL as a leaf, or nothing when it cannot emit.
bool vpl_leaf(const Scene& scene, const Vpl& v, uint32_t index, float inv_sets, LightLeaf& leaf) {
  leaf.position = v.position;
  leaf.normal = v.normal;
  leaf.source = index;
  const glm::vec3 flux = v.flux * inv_sets;
  if (v.kind == VplKind::Area) {
    leaf.light_class = LightClass::Cosine;
    leaf.intensity = flux;
  } else if (scene.materials[v.material].type == MaterialType::Diffuse) {
    leaf.light_class = LightClass::Cosine;
    leaf.intensity = v.albedo * kInvPi * flux;
  } else if (scene.materials[v.material].type == MaterialType::MetallicRoughness) {
    // Both lobes: f_y cos_y <= (1 - metallic) base / pi + F D_max / (4 cos_incident), F <= specular_bound.
    const float cos_incident = glm::dot(v.incident, v.normal);
    if (!(cos_incident > 0.0f)) return false;
    const Material& m = scene.materials[v.material];
    leaf.light_class = LightClass::Glossy;
    leaf.intensity = flux;
    leaf.spread = 0.5f * kPi;
    const float lobe = v.diffuse_only ? 0.0f : specular_bound(m.specular_weight, v.metallic) * ggx_distribution(1.0f, v.alpha) /
                                                   (4.0f * cos_incident);
    leaf.weight = max_component(flux * ((1.0f - v.metallic) * kInvPi * v.albedo + glm::vec3(lobe)));
    return leaf.weight > 0.0f && std::isfinite(leaf.weight);
  } else {
    // GGX conductor: f_y cos_y = F D G2 / (4 cos_incident) <= F D_max / (4 cos_incident).
    const float cos_incident = glm::dot(v.incident, v.normal);
    if (!(cos_incident > 0.0f)) return false;  // bsdf_eval gives 0 for every direction
    leaf.light_class = LightClass::Glossy;
    leaf.intensity = flux;
    leaf.spread = 0.5f * kPi;
    const float d_max = ggx_distribution(1.0f, scene.materials[v.material].alpha);
    leaf.weight = max_component(flux * v.albedo) * d_max / (4.0f * cos_incident);
    return leaf.weight > 0.0f && std::isfinite(leaf.weight);
  }
  leaf.weight = max_component(leaf.intensity);
  return leaf.weight > 0.0f;
}

LightLeaf punctual_leaf(const PunctualLight& light, uint32_t index) {
  LightLeaf leaf;
  leaf.source = index;
  leaf.scene_light = true;
  leaf.intensity = light.intensity;
  leaf.weight = max_component(light.intensity);
  switch (light.type) {
    case LightType::Directional:
      leaf.light_class = LightClass::Directional;
      leaf.position = -glm::normalize(light.direction);
      break;
    case LightType::Spot:
      leaf.light_class = LightClass::Punctual;
      leaf.position = light.position;
      leaf.normal = glm::normalize(light.direction);
      leaf.spread = light.outer_cone;
      break;
    default:
      leaf.light_class = LightClass::Punctual;
      leaf.position = light.position;
      leaf.normal = glm::vec3(0.0f, 0.0f, 1.0f);
      leaf.spread = kPi;
  }
  return leaf;
}

}  // namespace

std::vector<LightLeaf> make_light_leaves(const Scene& scene, const VplSets& vpls, bool scene_lights) {
  std::vector<LightLeaf> leaves;
  leaves.reserve(vpls.vpls.size() + scene.lights.size());
  const float inv_sets = 1.0f / float(std::max(1, vpls.set_count()));
  for (uint32_t i = 0; i < vpls.vpls.size(); ++i) {
    const Vpl& v = vpls.vpls[i];
    LightLeaf leaf;
    if (v.kind == VplKind::Directional) {  // the environment's, from a direction
      leaf.light_class = LightClass::Directional;
      leaf.position = -v.normal;
      leaf.intensity = v.flux * inv_sets;
      leaf.weight = max_component(leaf.intensity);
      leaf.source = i;
      if (leaf.weight > 0.0f) leaves.push_back(leaf);
      continue;
    }
    if (v.kind != VplKind::Surface && v.kind != VplKind::Area) continue;  // punctual: from the scene
    if (vpl_leaf(scene, v, i, inv_sets, leaf)) leaves.push_back(leaf);
  }
  for (uint32_t i = 0; scene_lights && i < scene.lights.size(); ++i) {
    LightLeaf leaf = punctual_leaf(scene.lights[i], i);
    if (leaf.weight > 0.0f) leaves.push_back(leaf);
  }
  return leaves;
}

}  // namespace igi::lightcuts
