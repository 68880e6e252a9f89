#include "lightcuts/light_sampler.h"

#include <algorithm>
#include <cmath>

#include "lightcuts/cluster_bound.h"
#include "sampling/sobol.h"

namespace igi::lightcuts {
namespace {

float luminance(glm::vec3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

bool drawn(LightClass c) { return c != LightClass::Punctual; }

}  // namespace

LightSampler::LightSampler(const LightTree& tree, float clamp_bound, float min_distance2)
    : tree_(tree), clamp_bound_(clamp_bound), min_distance2_(min_distance2) {}

float LightSampler::importance(const GatherPoint& g, uint32_t n) const {
  const LightNode& light = tree_.nodes[n];
  const bool directional = light.light_class == LightClass::Directional;
  const glm::vec3 p = g.surface.position;
  const Box directions = directional ? light.box : Box{light.box.lo - p, light.box.hi - p};
  const float y = light_factor(light, directions);
  if (y <= 0.0f) return 0.0f;
  const ReceiverTerms r = receiver_terms(g, directions);
  float inv_d2 = 1.0f;
  if (!directional) {
    const glm::vec3 centre = 0.5f * (directions.lo + directions.hi);
    const float half = 0.5f * light.box.diagonal();
    inv_d2 = 1.0f / std::max({glm::dot(centre, centre), half * half, min_distance2_});
  }
  const float b = light.light_class == LightClass::Cosine ? clamp_bound_ : INFINITY;
  glm::vec3 terms = r.glossy * (y * inv_d2);
  if (r.cos_x > 0.0f) terms += r.diffuse * std::min(r.cos_x * y * inv_d2, b);
  return luminance(terms) * light.weight;
}

double LightSampler::left_probability(const GatherPoint& g, uint32_t n) const {
  const double a = importance(g, n + 1), b = importance(g, tree_.nodes[n].right);
  return a + b > 0.0 ? a / (a + b) : 0.5;
}

std::optional<LightDraw> LightSampler::draw(const GatherPoint& g, double u) const {
  // The roots first, as children of one virtual root.
  float root_importance[kLightClasses] = {};
  double total = 0.0;
  for (size_t i = 0; i < tree_.roots.size(); ++i) {
    const uint32_t r = tree_.roots[i];
    if (drawn(tree_.nodes[r].light_class)) root_importance[i] = importance(g, r);
    total += root_importance[i];
  }
  if (!(total > 0.0)) return std::nullopt;
  u *= total;
  size_t last = 0;  // the last root that can be drawn: u rounded past the others lands there
  for (size_t i = 0; i < tree_.roots.size(); ++i)
    if (root_importance[i] > 0.0f) last = i;
  size_t chosen = last;
  double below = 0.0;
  for (size_t i = 0; i < last; ++i) {
    if (root_importance[i] <= 0.0f) continue;
    if (u < below + root_importance[i]) {
      chosen = i;
      break;
    }
    below += root_importance[i];
  }
  uint32_t n = tree_.roots[chosen];
  double pdf = root_importance[chosen] / total;
  u = std::clamp((u - below) / root_importance[chosen], 0.0, std::nextafter(1.0, 0.0));
  while (!tree_.nodes[n].is_leaf()) {
    const uint32_t left = n + 1, right = tree_.nodes[n].right;
    const double p = left_probability(g, n);
    if (u < p) {
      n = left, pdf *= p, u /= p;
    } else {
      n = right, pdf *= 1.0 - p, u = std::min(1.0, (u - p) / (1.0 - p));
    }
  }
  return LightDraw{n, pdf};
}

double LightSampler::probability(const GatherPoint& g, uint32_t target) const {
  if (!drawn(tree_.nodes[target].light_class)) return 0.0;
  double total = 0.0, chosen = 0.0;
  uint32_t n = 0;
  for (uint32_t r : tree_.roots) {
    if (!drawn(tree_.nodes[r].light_class)) continue;
    const double i = importance(g, r);
    total += i;
    if (r <= target && target < tree_.nodes[r].end) chosen = i, n = r;
  }
  if (!(total > 0.0) || chosen <= 0.0) return 0.0;
  double p = chosen / total;
  while (n != target) {
    const uint32_t left = n + 1, right = tree_.nodes[n].right;
    const double q = left_probability(g, n);
    const bool go_left = target < right;
    p *= go_left ? q : 1.0 - q;
    n = go_left ? left : right;
  }
  return p;
}

double LightSampler::draw_u(uint32_t j, uint32_t seed) {
  const glm::vec2 v = sample_2d(j, 0, seed);
  return double(v.x) + double(v.y) * 0x1p-24;  // sample_2d gives multiples of 2^-24
}

}  // namespace igi::lightcuts
