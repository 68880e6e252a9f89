#pragma once
// Reconstruction cuts (after Walter et al. 2005, sec. 5): full cuts with
// shadow rays only at a sparse grid of image samples; every other pixel
// takes the visibility of its clusters from the samples at the corners of
// its grid cell wherever they agree.
//
// The grid is in GLOBAL image coordinates: sample columns at x = k s
// (k = 0, 1, ...) plus the last column x = width - 1, rows alike. A pixel's
// value depends only on its own gather point and the cuts of its cell's
// corner samples, so a tile computes the samples around it even where they
// lie outside it, and tiles of any size give the same pixels.
//
// A pixel uses the corner samples that see the same surface (same material,
// normals within 25 degrees, within 2 % of its depth of the sample's plane);
// with fewer than two it takes a plain cut. Otherwise its cut is selected
// exactly like a plain cut, by its own error bounds, but a cluster's
// visibility comes from the samples when their cuts agree on it: every
// node of a sample's cut inside the cluster (or the node of the sample's cut
// that holds the cluster) found visible, or every one found occluded. Where
// they disagree, or saw nothing there, the pixel casts its own shadow ray. So
// rays go where neighbouring cuts disagree: along shadow edges.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "lightcuts/cut_node.h"
#include "lightcuts/gather_points.h"
#include "lightcuts/light_tree.h"

namespace igi::lightcuts {

// One axis of the sample grid.
struct SampleAxis {
  int spacing = 8;
  int size = 0;  // pixels along the axis

  int cell(int x) const { return x / spacing; }  // cell k spans [k s, (k + 1) s)
  int coordinate(int k) const { return std::min(k * spacing, size - 1); }
  // The sample index at pixel x, or -1 when no sample lies there.
  int sample_at(int x) const { return x % spacing == 0 ? x / spacing : x == size - 1 ? cell(x) + 1 : -1; }
};

// Whether sample q sees the surface pixel p sees.
inline bool same_surface(const GatherPoint& p, const GatherPoint& q) {
  if (!p.valid() || !q.valid() || p.surface.material != q.surface.material) return false;
  if (glm::dot(p.shading_normal, q.shading_normal) < 0.9f) return false;
  const float plane_distance = std::abs(glm::dot(q.geometric_normal, p.surface.position - q.surface.position));
  return plane_distance <= 0.02f * p.depth;
}

// What a sample's cut says about the visibility of a light node's cluster.
enum class SampleSays : uint8_t {
  Nothing,   // no ray anywhere in it (its light did not reach the sample)
  Visible,   // every ray in it unoccluded
  Occluded,  // every ray in it occluded
  Mixed,
};

inline SampleSays combine(SampleSays a, SampleSays b) {
  if (a == SampleSays::Nothing) return b;
  if (b == SampleSays::Nothing || a == b) return a;
  return SampleSays::Mixed;
}

// A sample's cut, readable per node: for each node at or above the cut
// (the cut's nodes and their ancestors) what the sample says about it, and
// whether it is a node of the cut. Nodes below the cut are not stored: they
// take what the sample says about the cut node above them.
class SampleVisibility {
 public:
  void build(const LightTree& tree, const std::vector<CutNode>& cut);

  struct Answer {
    bool found = false;   // at or above the cut
    bool in_cut = false;  // a node of the cut: its descendants take `says`
    SampleSays says = SampleSays::Nothing;
  };
  Answer at(uint32_t node) const;

 private:
  SampleSays visit(const LightTree& tree, uint32_t node, const std::vector<CutNode>& cut, size_t& cursor);
  void insert(uint32_t node, bool in_cut, SampleSays says);

  // Open addressing, linear probing; key node + 1 (0: empty).
  std::vector<uint32_t> keys_;
  std::vector<uint8_t> values_;  // says | in_cut << 2
  uint32_t mask_ = 0;
};

}  // namespace igi::lightcuts
