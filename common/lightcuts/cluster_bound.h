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
//   diffuse albedo / pi of Lambertian receivers
//   glossy  a bound on f cos_x of GGX receivers: f cos_x = F D G2 / (4 cos_o)
//           with G2 <= 1 and D growing with cos(h, n). For one point,
//           cos(h, n) = (cos_o + cos_i) / |wo + wi| <= (cos_o + max cos_i) /
//           sqrt(2 + 2 min(wo . wi)) over B; for a cluster D <= D(h = n).
// Errors are compared in luminance.
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

ReceiverTerms receiver_terms(const GatherPoint& g, const Box& directions);
ReceiverTerms receiver_terms(const GatherNode& node, const Box& directions);

// The light's directional factor Y over `directions` (gather to light).
float light_factor(const LightNode& light, const Box& directions);

// The bound of the pair, per channel.
glm::vec3 pair_bound(const GatherTree& gather, uint32_t gather_node, const LightNode& light, float clamp_bound);

}  // namespace igi::lightcuts
