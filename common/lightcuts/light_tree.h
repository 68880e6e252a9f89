#pragma once
// The light tree of Lightcuts: a binary tree over the leaves of
// lightcuts/light_leaves.h, one subtree (root) per light class.
//
// A node stores what its error bound needs (bounding box of the positions,
// bounding cone of the normals, for oriented lights the reach of their
// emission, total weight W) and a representative leaf. The representative
// is chosen at each inner node from the two children's representatives with
// probability proportional to their weights, from a number hashed from the
// frame seed and the node index (a pure function of both), so a leaf is the
// representative of a node with probability w_leaf / W_node: the cluster
// estimate  c(representative) W_node / w_leaf  is unbiased, and a node's
// representative is also that of one of its children (the cut reuses its
// shadow ray when it refines the node).
//
// Build: top-down, O(N log N): each node splits its leaves at the median of
// the axis with the largest extent, among the three of position and, for
// oriented lights, the three of the normal scaled by half the scene's
// diagonal (the paper's c in I (a^2 + c^2 (1 - cos b)^2)). Ties are broken by
// leaf index, so the tree is the same on every worker; its content hash
// joins the method's frame_state_hash.
//
// Layout: nodes in depth-first pre-order. A node's left child follows it, its
// right child is at `right`, and its subtree ends before `end`, so "node m
// lies in the subtree of node n" is n <= m < nodes[n].end.
#include <cstdint>
#include <vector>

#include "lightcuts/bounds.h"
#include "lightcuts/light_leaves.h"

namespace igi::lightcuts {

struct LightNode {
  Box box;                    // of the leaves' positions (Directional: unit directions)
  Cone cone;                  // of the leaves' normals (Cosine, Glossy, spots)
  float cos_reach = -1.0f;    // cos(theta + spread), -1 beyond pi: step emitters (Glossy, Punctual)
  float weight = 0.0f;        // W: sum of the leaves' weights
  float weight_over_representative = 0.0f;  // W / w of the representative leaf: the cluster's scale
  uint32_t representative = 0;  // a leaf index
  uint32_t right = 0;         // 0 for a leaf (a root is never a right child)
  uint32_t end = 0;           // one past the last node of the subtree
  uint32_t leaf = 0;          // leaves only: index into LightTree::leaves
  LightClass light_class = LightClass::Cosine;
  bool is_leaf() const { return right == 0; }
};

struct LightTree {
  std::vector<LightLeaf> leaves;
  std::vector<LightNode> nodes;
  std::vector<uint32_t> roots;  // one per light class present
  uint64_t hash = 0;
};

// `scene_diagonal` scales normals against positions in the split choice.
LightTree build_light_tree(std::vector<LightLeaf> leaves, float scene_diagonal, uint32_t seed);

uint64_t hash_light_tree(const LightTree& tree);

}  // namespace igi::lightcuts
