#include "lightcuts/cluster_bound.h"

#include <algorithm>
#include <cmath>

namespace igi::lightcuts {
namespace {

// v s, where 0 times an infinite s is 0 (a black channel stays black).
glm::vec3 scaled(glm::vec3 v, float s) {
  return {v.x > 0.0f ? v.x * s : 0.0f, v.y > 0.0f ? v.y * s : 0.0f, v.z > 0.0f ? v.z * s : 0.0f};
}

}  // namespace

ReceiverTerms receiver_terms(const GatherPoint& g, const Box& directions) {
  ReceiverTerms t;
  // Light from behind the geometric surface reaches no BSDF (vpl_contribution.h).
  const float cos_geometric = max_cos(g.geometric_frame, directions);
  if (cos_geometric <= 0.0f) return t;
  const bool tilted = g.tilt_sin > 0.0f;
  const float cos_above = tilted ? std::max(0.0f, max_cos(g.shading_frame, directions)) : cos_geometric;
  const Material& m = *g.surface.material;
  if (m.type == MaterialType::Diffuse) {
    t.diffuse = g.surface.albedo * kInvPi;
    // |cos_x| uses the shading normal n_s, tilted by d from the geometric n_g:
    // above the geometric plane, cos(w, n_s) >= -sin d.
    t.cos_x = std::max(cos_above, g.tilt_sin);
    return t;
  }
  if (cos_above <= 0.0f || g.cos_o <= 0.0f) return t;  // GGX reflects only above its shading normal
  const float min_wo_wi = -max_cos(g.back_frame, directions);
  const float denominator = std::sqrt(std::max(0.0f, 2.0f + 2.0f * min_wo_wi));
  const float cos_h = denominator > 0.0f ? std::min(1.0f, (g.cos_o + cos_above) / denominator) : 1.0f;
  t.glossy = g.surface.albedo * (ggx_distribution(cos_h, m.alpha) / (4.0f * g.cos_o));
  return t;
}

ReceiverTerms receiver_terms(const GatherNode& node, const Box& directions) {
  ReceiverTerms t;
  Cone below = node.cone;
  below.frame = Onb(-node.cone.axis());
  t.cos_x = std::max(max_cos(node.cone, directions), max_cos(below, directions));
  if (t.cos_x <= 0.0f) return t;
  t.diffuse = node.diffuse;
  t.glossy = node.glossy;
  return t;
}

float light_factor(const LightNode& light, const Box& directions) {
  switch (light.light_class) {
    case LightClass::Cosine: return max_cos(light.cone, negated(directions));
    case LightClass::Directional: return 1.0f;
    default: return within_reach(light.cone.frame, light.cos_reach, negated(directions)) ? 1.0f : 0.0f;
  }
}

glm::vec3 pair_bound(const GatherTree& gather, uint32_t gather_node, const LightNode& light, float clamp_bound) {
  const GatherNode& g = gather.nodes[gather_node];
  const bool directional = light.light_class == LightClass::Directional;
  const Box directions = directional ? light.box : difference(light.box, g.box);
  const float y = light_factor(light, directions);
  if (y <= 0.0f) return glm::vec3(0.0f);
  const ReceiverTerms r = g.is_leaf() ? receiver_terms(gather.points[g.representative], directions)
                                      : receiver_terms(g, directions);
  const float inv_d2 = directional ? 1.0f : 1.0f / distance2(directions);  // may be infinite
  const float b = light.light_class == LightClass::Cosine ? clamp_bound : INFINITY;
  glm::vec3 bound(0.0f);
  if (r.cos_x > 0.0f) bound += scaled(r.diffuse, std::min(r.cos_x * y * inv_d2, b));
  bound += scaled(r.glossy, y * inv_d2);
  return scaled(bound, g.strength * light.weight);
}

}  // namespace igi::lightcuts
