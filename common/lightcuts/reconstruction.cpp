#include "lightcuts/reconstruction.h"


namespace igi::lightcuts {
namespace {

uint32_t slot(uint32_t node, uint32_t mask) { return (node * 0x9e3779b1u >> 7) & mask; }

}  // namespace

void SampleVisibility::build(const LightTree& tree, const std::vector<CutNode>& cut) {
  // At most two nodes at or above the cut per cut node; a table at most half full.
  uint32_t capacity = 16;
  while (capacity < 4 * cut.size() + 8) capacity *= 2;
  keys_.assign(capacity, 0);
  values_.assign(capacity, 0);
  mask_ = capacity - 1;
  size_t cursor = 0;  // the cut is sorted, and visit() walks in pre-order
  for (uint32_t root : tree.roots) visit(tree, root, cut, cursor);
}

// Pre-order walk down to the cut; returns what the sample says about `node`.
SampleSays SampleVisibility::visit(const LightTree& tree, uint32_t node, const std::vector<CutNode>& cut,
                                   size_t& cursor) {
  if (cursor < cut.size() && cut[cursor].light == node) {
    const Visibility v = cut[cursor++].visibility;
    const SampleSays says = v == Visibility::Visible    ? SampleSays::Visible
                            : v == Visibility::Occluded ? SampleSays::Occluded
                                                        : SampleSays::Nothing;
    insert(node, true, says);
    return says;
  }
  const LightNode& n = tree.nodes[node];
  if (n.is_leaf() || cursor >= cut.size() || cut[cursor].light >= n.end) {
    insert(node, true, SampleSays::Nothing);  // not covered by the cut (cannot happen for a full cut)
    return SampleSays::Nothing;
  }
  const SampleSays left = visit(tree, node + 1, cut, cursor);
  const SampleSays says = combine(left, visit(tree, n.right, cut, cursor));
  insert(node, false, says);
  return says;
}

void SampleVisibility::insert(uint32_t node, bool in_cut, SampleSays says) {
  uint32_t i = slot(node, mask_);
  while (keys_[i] != 0) i = (i + 1) & mask_;
  keys_[i] = node + 1;
  values_[i] = uint8_t(uint8_t(says) | (in_cut ? 4 : 0));
}

SampleVisibility::Answer SampleVisibility::at(uint32_t node) const {
  for (uint32_t i = slot(node, mask_);; i = (i + 1) & mask_) {
    if (keys_[i] == 0) return {};
    if (keys_[i] == node + 1) return {true, (values_[i] & 4) != 0, SampleSays(values_[i] & 3)};
  }
}

}  // namespace igi::lightcuts
