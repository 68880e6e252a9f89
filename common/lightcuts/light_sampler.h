#pragma once
// Stochastic lightcuts (Yuksel, HPG 2019): a shading point draws K lights
// from the light tree (lightcuts/light_tree.h), each evaluated with one
// shadow ray and divided by the probability of drawing it: an unbiased
// estimate of the same sum that lightcuts' cut and ir's gather estimate over
// the same VPLs. Where a cut or an interleaved set leaves correlated errors
// (blotches), the draws leave fine per-point noise. igi's --vpl-draws is the
// caller (methods/vpl_draws.h).
//
// A draw walks from the roots down. At each choice it takes a child with
// probability proportional to the child's importance at the gather point:
//
//   importance = W [ diffuse min(cos_x Y / d^2, b) + glossy Y / d^2 ]   (luminance)
//
// the terms of the cluster bound (lightcuts/cluster_bound.h: the receiver's
// BSDF and cosine bounds, the light's directional factor Y, the clamp b of
// Cosine lights) but with d^2 the squared distance to the cluster's centre,
// at least (half its diagonal)^2 (Yuksel's choice: the bound's distance to the
// box is 0 for every cluster around the point, which says nothing), and at
// least `min_distance2` (a leaf on the point itself). Directional clusters
// (the environment's VPLs and the scene's directional lights) have d^2 = 1.
// An importance is 0 only where the bound is 0, where no leaf below can add
// light, so every leaf that can is drawn with a probability above 0. On a
// sharp GGX receiver the bound of every cluster whose box holds the mirror
// direction is the lobe's peak, far above what its lights bring, so a few
// lights that do bring light get probabilities near 1e-8: unbiased, but a
// heavy tail (igi gathers such surfaces with rays, methods/glossy_gather.h).
//
// One uniform number u per draw chooses the whole path: at a choice with
// probability p for the left child, u < p goes left as u / p, else right as
// (u - p) / (1 - p) (pbrt-v4's light BVH). So K stratified u's stratify the
// leaves in tree order, which is space. u is a double: a float has too few
// bits for 20 levels.
//
// Point and spot lights (the Punctual class) are few and exact: never drawn,
// the caller adds them (igi's exact lights, core/direct_lights.h).
//
// Where both children's bounds are 0 but their parent's is not (the
// children's boxes are tighter), no leaf below can light the point; the draw
// takes either child at even odds, so that it always ends on a leaf and the
// probabilities of the drawable leaves sum to 1.
#include <cstdint>
#include <optional>

#include "core/frame.h"
#include "lightcuts/gather_points.h"
#include "lightcuts/light_tree.h"

namespace igi::lightcuts {

struct LightDraw {
  uint32_t node = 0;  // the leaf's node in LightTree::nodes
  double pdf = 0.0;   // the probability of drawing it
};

class LightSampler {
 public:
  // clamp_bound: the clamp on Cosine leaves' G (infinity when off), as in LightingContext.
  LightSampler(const LightTree& tree, float clamp_bound, float min_distance2);

  // The importance of node `n` at `g` (see above); 0 only when the node's bound is 0.
  float importance(const GatherPoint& g, uint32_t n) const;
  // The drawn leaf for u in [0, 1), or nothing when no drawable light can reach g.
  std::optional<LightDraw> draw(const GatherPoint& g, double u) const;
  // The probability that draw() returns leaf node `n` (0 for Punctual leaves).
  double probability(const GatherPoint& g, uint32_t n) const;

  // The u of draw j of a stream seeded with `seed`: Sobol sample j, 48 bits.
  static double draw_u(uint32_t j, uint32_t seed);

 private:
  double left_probability(const GatherPoint& g, uint32_t inner_node) const;

  const LightTree& tree_;
  float clamp_bound_;
  float min_distance2_;
};

}  // namespace igi::lightcuts
