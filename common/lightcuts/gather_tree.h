#pragma once
// The gather side of multidimensional lightcuts (Walter, Arbree, Bala and
// Greenberg 2006): a binary tree over one pixel's gather points, so a cut of
// the product graph (gather node x light node) can treat several gather
// points against one light cluster as one pair with one shadow ray.
//
// A gather point j has strength s_j = max(throughput_j) / K (K gather points
// per pixel, a box filter); a node stores the total strength S, the box of
// its points, the cone of their (viewer-facing) shading normals and bounds of
// their materials, and a representative point chosen with probability
// s_j / S from a number hashed from the frame seed, the pixel and the node.
// Plain lightcuts are the case K = 1: one leaf.
#include <cstdint>
#include <span>
#include <vector>

#include "lightcuts/bounds.h"
#include "lightcuts/gather_points.h"

namespace igi::lightcuts {

struct GatherNode {
  Box box;
  Cone cone;                     // of the points' shading normals (facing the viewer)
  float strength = 0.0f;         // S
  glm::vec3 diffuse{0.0f};       // max albedo / pi over the Lambertian points
  glm::vec3 glossy{0.0f};        // max F D_max / (4 cos_o) over the GGX points
  uint32_t representative = 0;   // index into GatherTree::points
  uint32_t left = 0, right = 0;  // children; both 0 for a leaf
  bool is_leaf() const { return left == 0 && right == 0; }
};

struct GatherTree {
  std::vector<GatherPoint> points;  // valid points with strength > 0 only
  std::vector<float> strength;      // s_j, per point
  std::vector<GatherNode> nodes;    // root first (empty when no point is valid)
  float inv_samples = 1.0f;         // 1 / K

  // Builds over `points` (the pixel's K gather points; invalid ones are left
  // out). Reuses its vectors: one tree per thread, rebuilt per pixel.
  void build(std::span<const GatherPoint> candidates, int samples_per_pixel, uint32_t seed);
  bool empty() const { return nodes.empty(); }
};

}  // namespace igi::lightcuts
