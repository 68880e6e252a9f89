#pragma once
// The error bound of a pair (gather node, light node): an upper bound on
// the pair's whole unoccluded contribution, with visibility bounded by 1
// (Walter et al. 2005, sec. 4.1; for gather nodes, 2006, sec. 4):
//
//   bound = S_gather W_light [ diffuse min(cos_x Y / d^2, b) + glossy Y / d^2 ]
//
// over the box B of vectors from the gather points to the lights:
//   d^2     the squared distance from the origin to B (1 for directional lights)
//   cos_x   |cos| between B and the receivers' shading normals
//   Y       the light's directional factor: Cosine lights max cos_y over their
//           cone of normals and -B; Glossy VPLs and Punctual lights 1 if -B
//           meets the reach of their emission, else 0; Directional 1
//   b       the clamp on G, for Cosine lights only (it bounds G, not f_y G)
//   diffuse albedo / pi of Lambertian receivers, (1 - metallic) base / pi of
//           metallic-roughness ones (their diffuse lobe; its Fresnel factor <= 1)
//   glossy  a bound on f cos_x of GGX receivers: f cos_x = F D G2 / (4 cos_o)
//           with G2 <= 1 and D growing with cos(h, n). For one point,
//           cos(h, n) = (cos_o + cos_i) / |wo + wi| <= (cos_o + max cos_i) /
//           sqrt(2 + 2 min(wo . wi)) over B; for a cluster D <= D(h = n).
//           For the metallic-roughness model F <= (1 - metallic) w + metallic
//           (material/metallic_roughness.h). Its lobe clamp (core/clamp.h)
//           only lowers what these bound.
// Errors are compared in luminance.
#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

#include "lightcuts/gather_tree.h"
#include "lightcuts/light_tree.h"

namespace igi::lightcuts {

// The receiver's terms for one gather point (tight) or a gather node.
struct ReceiverTerms {
  glm::vec3 diffuse{0.0f};  // albedo / pi
  float cos_x = 0.0f;       // bound of |cos_x| for the diffuse part
  glm::vec3 glossy{0.0f};   // bound of f cos_x for the GGX part
};

ReceiverTerms receiver_terms(const GatherNode& node, const Box& directions);

// The rest is inline: a cut evaluates it at every node, and inlined into the
// cut its divisions and square roots overlap (measured: 3 % of a cut).
namespace bound_detail {
// v s, where 0 times an infinite s is 0 (a black channel stays black).
inline glm::vec3 scaled(glm::vec3 v, float s) {
  return {v.x > 0.0f ? v.x * s : 0.0f, v.y > 0.0f ? v.y * s : 0.0f, v.z > 0.0f ? v.z * s : 0.0f};
}
}  // namespace bound_detail

// The terms of one gather point.
inline ReceiverTerms receiver_terms(const GatherPoint& g, const Box& directions) {
  ReceiverTerms t;
  // Light from behind the geometric surface reaches no BSDF (vpl_contribution.h).
  const float cos_geometric = max_cos(g.geometric_frame, directions);
  if (cos_geometric <= 0.0f) return t;
  const bool tilted = g.tilt_sin > 0.0f;
  const float cos_above = tilted ? std::max(0.0f, max_cos(g.shading_frame, directions)) : cos_geometric;
  const Material& m = *g.surface.material;
  const bool layered = m.type == MaterialType::MetallicRoughness;
  if (m.type == MaterialType::Diffuse || layered) {
    t.diffuse = (layered ? 1.0f - g.surface.metallic : 1.0f) * g.surface.albedo * kInvPi;
    // |cos_x| uses the shading normal n_s, tilted by d from the geometric n_g:
    // above the geometric plane, cos(w, n_s) >= -sin d.
    t.cos_x = std::max(cos_above, g.tilt_sin);
    if (!layered) return t;
  }
  if (cos_above <= 0.0f || g.cos_o <= 0.0f) return t;  // GGX reflects only above its shading normal
  const float min_wo_wi = -max_cos(g.back_frame, directions);
  const float denominator = std::sqrt(std::max(0.0f, 2.0f + 2.0f * min_wo_wi));
  const float cos_h = denominator > 0.0f ? std::min(1.0f, (g.cos_o + cos_above) / denominator) : 1.0f;
  const float lobe = ggx_distribution(cos_h, layered ? g.surface.alpha : m.alpha) / (4.0f * g.cos_o);
  t.glossy = layered ? glm::vec3(specular_bound(m.specular_weight, g.surface.metallic) * lobe) : g.surface.albedo * lobe;
  return t;
}

// The light's directional factor Y over `directions` (gather to light).
inline float light_factor(const LightNode& light, const Box& directions) {
  switch (light.light_class) {
    case LightClass::Cosine: return max_cos(light.cone, negated(directions));
    case LightClass::Directional: return 1.0f;
    default: return within_reach(light.cone.frame, light.cos_reach, negated(directions)) ? 1.0f : 0.0f;
  }
}

// The bound of the pair, per channel, for gather strength `strength` (the
// node's S; a block cut gives the largest of its points' strengths, to bound
// each point alone).
inline glm::vec3 pair_bound(const GatherTree& gather, uint32_t gather_node, const LightNode& light, float clamp_bound,
                            float strength) {
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
  if (r.cos_x > 0.0f) bound += bound_detail::scaled(r.diffuse, std::min(r.cos_x * y * inv_d2, b));
  bound += bound_detail::scaled(r.glossy, y * inv_d2);
  return bound_detail::scaled(bound, strength * light.weight);
}
inline glm::vec3 pair_bound(const GatherTree& gather, uint32_t gather_node, const LightNode& light, float clamp_bound) {
  return pair_bound(gather, gather_node, light, clamp_bound, gather.nodes[gather_node].strength);
}

}  // namespace igi::lightcuts
