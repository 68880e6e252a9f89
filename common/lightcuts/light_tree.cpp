#include "lightcuts/light_tree.h"

#include <algorithm>
#include <cmath>

#include "core/parallel.h"
#include "sampling/content_hash.h"
#include "sampling/hash.h"

namespace igi::lightcuts {
namespace {

bool oriented(LightClass c) { return c != LightClass::Directional; }

struct Range {
  uint32_t begin, end;  // positions in the build order, which becomes the leaves' order
};

// Builds subtrees over order[begin, end) (leaf indices of one class) in
// pre-order, recording each node's leaf range. Boxes and weights are filled
// on the way up; cones and representatives afterwards (fill_cones,
// choose_representatives), once the leaf order is final.
class Builder {
 public:
  Builder(const std::vector<LightLeaf>& leaves, std::vector<LightNode>& nodes, std::vector<Range>& ranges,
          std::vector<uint32_t>& order, float normal_scale)
      : leaves_(leaves), nodes_(nodes), ranges_(ranges), order_(order), normal_scale_(normal_scale) {}
  // Another builder over the same arrays, with scratch of its own (for another thread).
  Builder(const Builder& o) : Builder(o.leaves_, o.nodes_, o.ranges_, o.order_, o.normal_scale_) {}

  // Builds the subtree over order[begin, end) with its root at `index`: a
  // subtree of n leaves has 2n - 1 nodes, so where each subtree goes is known
  // before it is built, and the two halves of a large node are built at once.
  void build(uint32_t begin, uint32_t end, uint32_t index, int depth = 0) {
    ranges_[index] = {begin, end};
    LightNode& node = nodes_[index];
    if (end - begin == 1) {
      const LightLeaf& leaf = leaves_[order_[begin]];
      node.box.extend(leaf.position);
      node.weight = leaf.weight;
      node.leaf = node.representative = begin;  // the leaf's position once leaves are reordered
      node.end = index + 1;
      node.light_class = leaf.light_class;
      return;
    }
    // Deep down (a lopsided distribution), median splits bound the depth.
    const uint32_t mid = depth < kMaxBinnedDepth ? split(begin, end) : median_split(begin, end);
    const uint32_t right = index + 2 * (mid - begin);
    if (depth < kParallelDepth && end - begin >= kParallelLeaves) {
      parallel_pair([&] { Builder(*this).build(begin, mid, index + 1, depth + 1); },
                    [&] { build(mid, end, right, depth + 1); });
    } else {
      build(begin, mid, index + 1, depth + 1);
      build(mid, end, right, depth + 1);
    }
    const LightNode &l = nodes_[index + 1], &r = nodes_[right];
    node.right = right;
    node.end = index + 2 * (end - begin) - 1;
    node.box = l.box;
    node.box.extend(r.box);
    node.weight = l.weight + r.weight;
    node.light_class = l.light_class;
  }

 private:
  // Splits order[begin, end) in two and returns where the right part starts.
  // Candidates: kBins - 1 planes along each of the six axes (position, and
  // normal for oriented lights), binned by coordinate; the plane that
  // minimises the summed cluster cost of the two parts wins (first on ties).
  // With no plane that separates anything (all leaves in one bin), the
  // median of the widest axis, ties broken by leaf index.
  uint32_t split(uint32_t begin, uint32_t end) {
    if (end - begin <= kMedianBelow) return median_split(begin, end);
    const bool use_normals = oriented(leaves_[order_[begin]].light_class);
    const int axes = use_normals ? 6 : 3;
    Box position, normal;
    for (uint32_t i = begin; i < end; ++i) {
      position.extend(leaves_[order_[i]].position);
      if (use_normals) normal.extend(leaves_[order_[i]].normal);
    }
    float lo[6], scale[6];
    for (int a = 0; a < 6; ++a) {
      lo[a] = a < 3 ? position.lo[a] : normal.lo[a - 3];
      const float extent = (a < 3 ? position.hi[a] : normal.hi[a - 3]) - lo[a];
      scale[a] = a < axes && extent > 0.0f ? float(kBins) / extent : 0.0f;
    }
    // Large nodes bin a regular subsample of their leaves (at most kBinned):
    // the split plane needs the distribution, not every leaf.
    const uint32_t stride = std::max(1u, (end - begin) / kBinned);
    Bin bins[6][kBins];
    for (uint32_t i = begin; i < end; i += stride) {
      const LightLeaf& leaf = leaves_[order_[i]];
      for (int a = 0; a < axes; ++a)
        if (scale[a] > 0.0f) bins[a][bin_of(leaf, a, lo[a], scale[a])].add(leaf);
    }
    float best_cost = INFINITY;
    int best_axis = -1, best_plane = 0;
    for (int a = 0; a < axes; ++a) {
      if (!(scale[a] > 0.0f)) continue;
      Bin right[kBins];
      for (int b = kBins - 1; b > 0; --b) right[b - 1] = b == kBins - 1 ? bins[a][b] : merged(right[b], bins[a][b]);
      Bin left;
      for (int b = 0; b + 1 < kBins; ++b) {
        left = b == 0 ? bins[a][0] : merged(left, bins[a][b]);
        if (left.count == 0 || right[b].count == 0) continue;  // of the binned leaves
        const float c = cost(left) + cost(right[b]);
        if (c < best_cost) best_cost = c, best_axis = a, best_plane = b;
      }
    }
    if (best_axis < 0) return median_split(begin, end);
    // A stable partition, so the leaves' order (and with it the tree) depends on nothing but the input.
    scratch_.clear();
    uint32_t mid = begin;
    for (uint32_t i = begin; i < end; ++i) {
      const uint32_t leaf = order_[i];
      if (bin_of(leaves_[leaf], best_axis, lo[best_axis], scale[best_axis]) <= best_plane)
        order_[mid++] = leaf;
      else
        scratch_.push_back(leaf);
    }
    std::copy(scratch_.begin(), scratch_.end(), order_.begin() + mid);
    return mid;
  }

  static constexpr int kBins = 16;
  static constexpr uint32_t kBinned = 1024;
  static constexpr uint32_t kMedianBelow = 8;  // small nodes: binning costs more than it gains
  // The top two levels of large trees build their halves at once (core/parallel.h).
  static constexpr int kParallelDepth = 2;
  static constexpr uint32_t kParallelLeaves = 1 << 15;
  static constexpr int kMaxBinnedDepth = 48;

  struct Bin {
    Box position, normal;
    float weight = 0.0f;
    uint32_t count = 0;
    void add(const LightLeaf& leaf) {
      position.extend(leaf.position);
      normal.extend(leaf.normal);
      weight += leaf.weight;
      ++count;
    }
  };

  static Bin merged(Bin a, const Bin& b) {
    if (b.count == 0) return a;
    a.position.extend(b.position);
    a.normal.extend(b.normal);
    a.weight += b.weight;
    a.count += b.count;
    return a;
  }

  static int bin_of(const LightLeaf& leaf, int axis, float lo, float scale) {
    const float x = axis < 3 ? leaf.position[axis] : leaf.normal[axis - 3];
    return std::clamp(int((x - lo) * scale), 0, kBins - 1);
  }

  // The paper's cluster metric W (a^2 + c^2 (1 - cos b)^2), with the spread
  // b of the normals read off their box: chord d across the cone, 1 - cos b ~ d^2 / 8.
  float cost(const Bin& bin) const {
    const float a = bin.position.diagonal();
    const float d = bin.normal.diagonal();
    const float cone = normal_scale_ * d * d * 0.125f;
    return bin.weight * (a * a + cone * cone);
  }

  uint32_t median_split(uint32_t begin, uint32_t end) {
    const bool use_normals = oriented(leaves_[order_[begin]].light_class);
    Box position, normal;
    for (uint32_t i = begin; i < end; ++i) {
      position.extend(leaves_[order_[i]].position);
      if (use_normals) normal.extend(leaves_[order_[i]].normal);
    }
    float extent[6];
    for (int a = 0; a < 3; ++a) {
      extent[a] = position.hi[a] - position.lo[a];
      extent[3 + a] = use_normals ? (normal.hi[a] - normal.lo[a]) * normal_scale_ : 0.0f;
    }
    const int axis = int(std::max_element(extent, extent + 6) - extent);
    auto key = [&](uint32_t i) { return axis < 3 ? leaves_[i].position[axis] : leaves_[i].normal[axis - 3]; };
    const uint32_t mid = begin + (end - begin) / 2;
    std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                     [&](uint32_t a, uint32_t b) { return key(a) < key(b) || (key(a) == key(b) && a < b); });
    return mid;
  }

  const std::vector<LightLeaf>& leaves_;
  std::vector<LightNode>& nodes_;
  std::vector<Range>& ranges_;
  std::vector<uint32_t>& order_;
  float normal_scale_;
  std::vector<uint32_t> scratch_;
};

// The cone of each node's normals (axis: their normalised sum, in leaf order)
// and the reach of its emission (Glossy, Punctual: cone plus the widest spread).
void fill_cones(LightTree& tree, const std::vector<Range>& ranges, size_t first, size_t last) {
  for (size_t n = first; n < last; ++n) {
    LightNode& node = tree.nodes[n];
    if (node.light_class == LightClass::Directional) continue;
    glm::vec3 sum(0.0f);
    float spread = 0.0f;
    for (uint32_t i = ranges[n].begin; i < ranges[n].end; ++i) {
      sum += tree.leaves[i].normal;
      spread = std::max(spread, tree.leaves[i].spread);
    }
    const float length = glm::length(sum);
    float theta = kPi;
    if (length > 1e-6f) {
      node.cone.frame = BoundFrame(sum / length);
      float cos_min = 1.0f;
      for (uint32_t i = ranges[n].begin; i < ranges[n].end; ++i)
        cos_min = std::min(cos_min, glm::dot(node.cone.axis(), tree.leaves[i].normal));
      // A hair wider than measured: normals are unit only to rounding.
      theta = std::min(kPi, std::acos(std::clamp(cos_min, -1.0f, 1.0f)) + 1e-4f);
    }
    node.cone.cos_theta = theta >= kPi ? -1.0f : std::cos(theta);
    node.cone.sin_theta = theta >= kPi ? 0.0f : std::sin(theta);
    node.cos_reach = theta + spread >= kPi ? -1.0f : std::cos(theta + spread);
  }
}

// Children before parents: a node takes one child's representative with
// probability proportional to that child's weight.
void choose_representatives(LightTree& tree, uint32_t seed) {
  for (size_t n = tree.nodes.size(); n-- > 0;) {
    LightNode& node = tree.nodes[n];
    if (node.is_leaf()) continue;
    const LightNode &l = tree.nodes[n + 1], &r = tree.nodes[node.right];
    const float u = float(hash(seed, uint32_t(n)) >> 8) * 0x1p-24f;
    node.representative = u * node.weight < l.weight ? l.representative : r.representative;
  }
  for (LightNode& node : tree.nodes) node.weight_over_representative = node.weight / tree.leaves[node.representative].weight;
}

}  // namespace

LightTree build_light_tree(std::vector<LightLeaf> leaves, float scene_diagonal, uint32_t seed) {
  LightTree tree;
  std::vector<uint32_t> order(leaves.size());
  for (uint32_t i = 0; i < order.size(); ++i) order[i] = i;
  // One subtree per class, in class order.
  std::stable_sort(order.begin(), order.end(),
                   [&](uint32_t a, uint32_t b) { return leaves[a].light_class < leaves[b].light_class; });
  std::vector<std::pair<uint32_t, uint32_t>> classes;  // leaf ranges of one class each
  for (uint32_t begin = 0; begin < order.size();) {
    uint32_t end = begin;
    while (end < order.size() && leaves[order[end]].light_class == leaves[order[begin]].light_class) ++end;
    classes.push_back({begin, end});
    begin = end;
  }
  tree.nodes.resize(2 * leaves.size() - classes.size());
  std::vector<Range> ranges(tree.nodes.size());
  Builder builder(leaves, tree.nodes, ranges, order, 0.5f * scene_diagonal);
  uint32_t root = 0;
  for (auto [begin, end] : classes) {
    tree.roots.push_back(root);
    builder.build(begin, end, root);
    root += 2 * (end - begin) - 1;
  }
  // Leaves in pre-order: node.leaf (a build position) now indexes them.
  tree.leaves.reserve(leaves.size());
  for (uint32_t i : order) tree.leaves.push_back(leaves[i]);
  // Each node's cone reads its own leaves only: two halves at once.
  if (tree.nodes.size() < (1u << 16)) {
    fill_cones(tree, ranges, 0, tree.nodes.size());
  } else {
    const size_t half = tree.nodes.size() / 2;
    parallel_pair([&] { fill_cones(tree, ranges, 0, half); }, [&] { fill_cones(tree, ranges, half, tree.nodes.size()); });
  }
  choose_representatives(tree, hash(seed, 0x6c747265u /* "ltre" */));
  tree.hash = hash_light_tree(tree);
  return tree;
}

uint64_t hash_light_tree(const LightTree& tree) {
  // Every field that shading reads.
  ContentHasher h;
  auto word = [&h](uint32_t w) { h.add(w); };
  auto real = [&h](float f) { h.add(f); };
  for (const LightNode& n : tree.nodes) {
    for (int a = 0; a < 3; ++a) real(n.box.lo[a]), real(n.box.hi[a]), real(n.cone.frame.n[a]);
    real(n.cone.cos_theta);
    real(n.cos_reach);
    real(n.weight);
    word(n.representative);
    word(n.right);
    word(n.leaf);
  }
  return h.value();
}

}  // namespace igi::lightcuts
