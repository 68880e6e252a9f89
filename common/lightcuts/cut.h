#pragma once
// Cut selection (Walter et al. 2005, sec. 4) over the product of a pixel's
// gather tree and the light tree (multidimensional lightcuts, Walter et al.
// 2006; with one gather point, plain lightcuts).
//
// A cut starts at (gather root, light root) for each light class. Each pair
// is estimated by its representative pair alone, which costs one shadow ray:
//   estimate = c(j, i) V(j, i) thr_j / K  (S_gather / s_j) (W_light / w_i)
// and bounded by lightcuts/cluster_bound.h. The pair with the largest bound
// is refined (its light node split, or its gather node: whichever has the
// larger box, a leaf never) until every bound is below `error` times the
// luminance of the cut's total, or the cut has `max_cut` pairs. A child pair
// with the parent's representative pair reuses its result: no new ray.
// Exact pairs (two leaves) have no error. Pairs whose bound is 0 add nothing
// and cast no ray.
//
// Not thread-safe: one engine per thread (it keeps its scratch vectors).
#include <cstdint>
#include <span>
#include <vector>

#include "core/frame.h"
#include "lightcuts/cut_node.h"
#include "lightcuts/gather_tree.h"
#include "lightcuts/light_contribution.h"
#include "lightcuts/light_tree.h"
#include "lightcuts/reconstruction.h"

namespace igi::lightcuts {

struct CutSettings {
  float error = 0.02f;
  int max_cut = 1000;
};

struct CutStats {
  uint64_t cuts = 0;          // cuts computed (pixels, or samples)
  uint64_t cut_nodes = 0;     // pairs in the finished cuts
  uint64_t reused = 0;        // child pairs that took the parent's result
  uint64_t interpolated = 0;  // reconstruction: visibilities taken from the samples, no ray
  uint64_t reconstructed = 0; // reconstruction: pixels that used samples
  uint64_t blocked = 0;       // block cuts: points shaded by a block's shared cut
  CutStats& operator+=(const CutStats& o) {
    cuts += o.cuts; cut_nodes += o.cut_nodes; reused += o.reused;
    interpolated += o.interpolated; reconstructed += o.reconstructed; blocked += o.blocked;
    return *this;
  }
};

class CutEngine {
 public:
  CutEngine(const LightTree& tree, const LightingContext& lighting, const Accel& accel, CutSettings settings)
      : tree_(tree), lighting_(lighting), accel_(accel), settings_(settings) {}

  static constexpr size_t kMaxSamples = 4;

  // The light the pixel's gather points receive, throughput and 1/K included
  // (emission excluded). `cut`, when given, receives the finished cut sorted
  // by light node (one-point trees only). With `samples` (a reconstruction
  // cut, lightcuts/reconstruction.h; one-point trees, at most kMaxSamples),
  // a cluster's visibility comes from the samples where they agree on it.
  glm::vec3 shade(const GatherTree& gather, std::vector<CutNode>* cut, CutStats& stats, RayCounts& rays,
                  std::span<const SampleVisibility* const> samples = {});

  // A block cut: one light cut shared by the gather points of neighbouring
  // pixels (one point each, at most kMaxBlockPoints, all on Lambertian surfaces
  // within one cone of normals). Each node is bounded once for all of them
  // (over the box of their positions), and refined until every bound is
  // below `error` times the smallest of their totals, so each point's cut
  // keeps the plain cut's guarantee; each point's value is its own estimate
  // over the shared cut (its own shadow rays). Returns false, leaving `out`
  // alone, when the points do not qualify: shade them one by one then.
  static constexpr size_t kMaxBlockPoints = 64;
  bool shade_block(std::span<const GatherPoint> points, std::span<glm::vec3> out, CutStats& stats,
                   RayCounts& rays);

 private:
  struct Entry {
    glm::vec3 unit{0.0f};  // c V thr / K of the representative pair
    float scale = 0.0f;    // (S / s_j) (W / w_i)
    float error = 0.0f;
    uint32_t gather = 0, light = 0;  // the pair
    uint32_t point = 0, leaf = 0;    // its representatives
    Visibility visibility = Visibility::Unknown;
    bool alive = true;
    glm::vec3 estimate() const { return unit * scale; }
  };
  // Per reconstruction sample: what it says about an entry's light node, and
  // whether the node lies at or below its cut (then children inherit that).
  // Kept beside the entries, and only for reconstruction cuts.
  struct SampleWords {
    SampleSays says[kMaxSamples] = {};
    bool covered[kMaxSamples] = {};
  };

  // `parent` is the entry being refined and `parent_words` its sample words
  // (null without samples); `words` receives the new entry's.
  Entry make_entry(const GatherTree& gather, uint32_t g, uint32_t l, const Entry* parent,
                   const SampleWords* parent_words, SampleWords& words, CutStats& stats, RayCounts& rays) const;
  void read_samples(uint32_t light, const SampleWords* parent_words, SampleWords& words) const;
  bool visible(const SampleWords& words, const Ray& shadow, CutStats& stats, RayCounts& rays) const;
  void add(const Entry& e, const SampleWords& words);
  void refine(const GatherTree& gather, CutStats& stats, RayCounts& rays);
  bool split_light(const GatherTree& gather, const Entry& e) const;

  const LightTree& tree_;
  LightingContext lighting_;
  const Accel& accel_;
  CutSettings settings_;
  // Scratch of the current cut.
  std::vector<Entry> entries_;
  std::vector<SampleWords> words_;  // per entry, with samples only
  struct HeapItem {
    float error;
    uint32_t entry;
    // Max-heap by error; equal errors: the older entry first (a total order, so the cut is deterministic).
    bool operator<(const HeapItem& o) const { return error < o.error || (error == o.error && entry > o.entry); }
  };
  std::vector<HeapItem> heap_;  // live entries with error > 0
  glm::dvec3 total_{0.0};
  size_t cut_size_ = 0;
  std::span<const SampleVisibility* const> samples_;

  // Scratch of the current block cut: per entry its light node, bound and
  // each point's unit estimate (one per point, from `first` in block_units_).
  struct BlockEntry {
    float error = 0.0f;
    uint32_t light = 0;
    uint32_t first = 0;  // into block_units_; kNone: nothing arrives
  };
  static constexpr uint32_t kNone = ~0u;
  void add_block_entry(std::span<const GatherPoint> points, float strength, uint32_t light, const BlockEntry* parent,
                       CutStats& stats, RayCounts& rays);
  std::vector<BlockEntry> block_entries_;
  std::vector<glm::vec3> block_units_;
  std::vector<glm::dvec3> block_totals_;
  GatherTree block_gather_;
};

}  // namespace igi::lightcuts
