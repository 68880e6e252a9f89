#include "lightcuts/gather_tree.h"

#include <algorithm>
#include <cmath>

#include "sampling/hash.h"
#include "sampling/warp.h"

namespace igi::lightcuts {
namespace {

// Material bounds of one point: Lambertian albedo / pi, or GGX F D_max / (4
// cos_o), or both for the metallic-roughness model (cluster_bound.h).
void material_bounds(const GatherPoint& g, glm::vec3& diffuse, glm::vec3& glossy) {
  const Material& m = *g.surface.material;
  if (m.type == MaterialType::Diffuse) {
    diffuse = glm::max(diffuse, g.surface.albedo * kInvPi);
  } else if (m.type == MaterialType::MetallicRoughness) {
    diffuse = glm::max(diffuse, (1.0f - g.surface.metallic) * g.surface.albedo * kInvPi);
    if (g.cos_o > 0.0f)
      glossy = glm::max(glossy, glm::vec3(specular_bound(m.specular_weight, g.surface.metallic) *
                                          (ggx_distribution(1.0f, g.surface.alpha) / (4.0f * g.cos_o))));
  } else if (g.cos_o > 0.0f) {
    glossy = glm::max(glossy, g.surface.albedo * (ggx_distribution(1.0f, m.alpha) / (4.0f * g.cos_o)));
  }
}

class Builder {
 public:
  Builder(GatherTree& tree, std::vector<uint32_t>& order) : tree_(tree), order_(order) {}

  uint32_t build(uint32_t begin, uint32_t end) {
    const uint32_t index = uint32_t(tree_.nodes.size());
    tree_.nodes.emplace_back();
    if (end - begin == 1) {
      const uint32_t j = order_[begin];
      GatherNode& node = tree_.nodes[index];
      node.box.extend(tree_.points[j].surface.position);
      node.cone.frame = tree_.points[j].shading_frame;
      node.strength = tree_.strength[j];
      node.representative = j;
      material_bounds(tree_.points[j], node.diffuse, node.glossy);
      return index;
    }
    const uint32_t mid = split(begin, end);
    const uint32_t left = build(begin, mid);
    const uint32_t right = build(mid, end);
    GatherNode& node = tree_.nodes[index];
    const GatherNode &l = tree_.nodes[left], &r = tree_.nodes[right];
    node.left = left;
    node.right = right;
    node.box = l.box;
    node.box.extend(r.box);
    node.strength = l.strength + r.strength;
    node.diffuse = glm::max(l.diffuse, r.diffuse);
    node.glossy = glm::max(l.glossy, r.glossy);
    fill_cone(node, begin, end);
    return index;
  }

 private:
  uint32_t split(uint32_t begin, uint32_t end) {
    Box box;
    for (uint32_t i = begin; i < end; ++i) box.extend(tree_.points[order_[i]].surface.position);
    const glm::vec3 extent = box.hi - box.lo;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
    auto key = [&](uint32_t j) { return tree_.points[j].surface.position[axis]; };
    const uint32_t mid = begin + (end - begin) / 2;
    std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                     [&](uint32_t a, uint32_t b) { return key(a) < key(b) || (key(a) == key(b) && a < b); });
    return mid;
  }

  void fill_cone(GatherNode& node, uint32_t begin, uint32_t end) {
    glm::vec3 sum(0.0f);
    for (uint32_t i = begin; i < end; ++i) sum += tree_.points[order_[i]].shading_normal;
    const float length = glm::length(sum);
    if (!(length > 1e-6f)) {
      node.cone.cos_theta = -1.0f;
      node.cone.sin_theta = 0.0f;
      return;
    }
    node.cone.frame = BoundFrame(sum / length);
    float cos_min = 1.0f;
    for (uint32_t i = begin; i < end; ++i)
      cos_min = std::min(cos_min, glm::dot(node.cone.axis(), tree_.points[order_[i]].shading_normal));
    const float theta = std::acos(std::clamp(cos_min, -1.0f, 1.0f)) + 1e-4f;
    node.cone.cos_theta = theta >= kPi ? -1.0f : std::cos(theta);
    node.cone.sin_theta = theta >= kPi ? 0.0f : std::sin(theta);
  }

  GatherTree& tree_;
  std::vector<uint32_t>& order_;
};

}  // namespace

void GatherTree::build(std::span<const GatherPoint> candidates, int samples_per_pixel, uint32_t seed) {
  points.clear();
  strength.clear();
  nodes.clear();
  inv_samples = 1.0f / float(samples_per_pixel);
  for (const GatherPoint& g : candidates) {
    const float s = max_component(g.throughput) * inv_samples;
    if (!g.valid() || !(s > 0.0f)) continue;
    points.push_back(g);
    strength.push_back(s);
  }
  if (points.empty()) return;
  thread_local std::vector<uint32_t> order;
  order.resize(points.size());
  for (uint32_t i = 0; i < order.size(); ++i) order[i] = i;
  Builder(*this, order).build(0, uint32_t(points.size()));
  // Representatives, children before parents (children follow their parent).
  for (size_t n = nodes.size(); n-- > 0;) {
    GatherNode& node = nodes[n];
    if (node.is_leaf()) continue;
    const GatherNode &l = nodes[node.left], &r = nodes[node.right];
    const float u = float(hash(seed, uint32_t(n)) >> 8) * 0x1p-24f;
    node.representative = u * node.strength < l.strength ? l.representative : r.representative;
  }
}

}  // namespace igi::lightcuts
