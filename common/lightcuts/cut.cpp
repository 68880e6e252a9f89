#include "lightcuts/cut.h"

#include <algorithm>

#include "lightcuts/cluster_bound.h"
#include "sampling/warp.h"

namespace igi::lightcuts {
namespace {

float luminance(glm::dvec3 c) { return float(0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z); }

}  // namespace

CutEngine::Entry CutEngine::make_entry(const GatherTree& gather, uint32_t g, uint32_t l, const Entry* parent,
                                       const SampleWords* parent_words, SampleWords& words, CutStats& stats,
                                       RayCounts& rays) const {
  const GatherNode& gn = gather.nodes[g];
  const LightNode& ln = tree_.nodes[l];
  Entry e;
  e.gather = g;
  e.light = l;
  e.point = gn.representative;
  e.leaf = ln.representative;
  if (!samples_.empty()) read_samples(l, parent_words, words);
  if (gn.is_leaf() && ln.is_leaf()) {
    e.scale = 1.0f;  // exact: no bound needed (the contribution says whether light arrives)
  } else {
    const glm::vec3 bound = pair_bound(gather, g, ln, lighting_.clamp_bound);
    if (!(bound.x > 0.0f || bound.y > 0.0f || bound.z > 0.0f)) return e;  // nothing can arrive
    e.scale = (gn.strength / gather.strength[e.point]) * ln.weight_over_representative;
    e.error = luminance(bound);
  }
  if (parent && parent->point == e.point && parent->leaf == e.leaf) {
    e.unit = parent->unit;
    e.visibility = parent->visibility;
    ++stats.reused;
    return e;
  }
  const GatherPoint& point = gather.points[e.point];
  Ray shadow;
  const glm::vec3 c = light_contribution(lighting_, point, tree_.leaves[e.leaf], shadow);
  if (c.x + c.y + c.z > 0.0f) {
    const bool lit = visible(words, shadow, stats, rays);
    e.visibility = lit ? Visibility::Visible : Visibility::Occluded;
    if (lit) e.unit = c * point.throughput * gather.inv_samples;
  }
  return e;
}

// What each reconstruction sample says about light node `light`: its
// parent's word when the parent lay at or below the sample's cut, else the
// sample's own record of the node.
void CutEngine::read_samples(uint32_t light, const SampleWords* parent_words, SampleWords& words) const {
  for (size_t q = 0; q < samples_.size(); ++q) {
    if (parent_words && parent_words->covered[q]) {
      words.says[q] = parent_words->says[q];
      words.covered[q] = true;
      continue;
    }
    const SampleVisibility::Answer a = samples_[q]->at(light);
    words.says[q] = a.says;
    words.covered[q] = !a.found || a.in_cut;
  }
}

// From the samples when they agree on the cluster, else by a shadow ray.
bool CutEngine::visible(const SampleWords& words, const Ray& shadow, CutStats& stats, RayCounts& rays) const {
  SampleSays says = SampleSays::Nothing;
  for (size_t q = 0; q < samples_.size(); ++q) says = combine(says, words.says[q]);
  if (says == SampleSays::Visible || says == SampleSays::Occluded) {
    ++stats.interpolated;
    return says == SampleSays::Visible;
  }
  ++rays.shadow;
  return !accel_.occluded(shadow);
}

void CutEngine::add(const Entry& e, const SampleWords& words) {
  entries_.push_back(e);
  if (!samples_.empty()) words_.push_back(words);
  total_ += glm::dvec3(e.estimate());
  ++cut_size_;
  if (e.error > 0.0f) {
    heap_.push_back({e.error, uint32_t(entries_.size() - 1)});
    std::push_heap(heap_.begin(), heap_.end());
  }
}

// Light node or gather node: a leaf is never split; directional light
// clusters live on the sphere of directions, not comparable with boxes.
bool CutEngine::split_light(const GatherTree& gather, const Entry& e) const {
  const GatherNode& gn = gather.nodes[e.gather];
  const LightNode& ln = tree_.nodes[e.light];
  if (gn.is_leaf()) return true;
  if (ln.is_leaf()) return false;
  if (ln.light_class == LightClass::Directional) return true;
  return ln.box.diagonal() >= gn.box.diagonal();
}

void CutEngine::refine(const GatherTree& gather, CutStats& stats, RayCounts& rays) {
  while (!heap_.empty() && cut_size_ < size_t(settings_.max_cut)) {
    const uint32_t worst = heap_.front().entry;
    if (heap_.front().error <= settings_.error * luminance(total_)) break;
    std::pop_heap(heap_.begin(), heap_.end());
    heap_.pop_back();
    entries_[worst].alive = false;
    const Entry parent = entries_[worst];  // a copy: adding children may move the entries
    SampleWords parent_words;
    if (!samples_.empty()) parent_words = words_[worst];
    total_ -= glm::dvec3(parent.estimate());
    --cut_size_;
    uint32_t children[2][2];  // (gather, light) of each child pair
    if (split_light(gather, parent)) {
      const uint32_t l = parent.light;
      children[0][0] = children[1][0] = parent.gather;
      children[0][1] = l + 1;
      children[1][1] = tree_.nodes[l].right;
    } else {
      const GatherNode& gn = gather.nodes[parent.gather];
      children[0][1] = children[1][1] = parent.light;
      children[0][0] = gn.left;
      children[1][0] = gn.right;
    }
    const SampleWords* from = samples_.empty() ? nullptr : &parent_words;
    SampleWords words;
    for (const auto& child : children)
      add(make_entry(gather, child[0], child[1], &parent, from, words, stats, rays), words);
  }
}

glm::vec3 CutEngine::shade(const GatherTree& gather, std::vector<CutNode>* cut, CutStats& stats, RayCounts& rays,
                           std::span<const SampleVisibility* const> samples) {
  entries_.clear();
  words_.clear();
  heap_.clear();
  total_ = glm::dvec3(0.0);
  cut_size_ = 0;
  samples_ = samples.first(std::min(samples.size(), kMaxSamples));
  if (cut) cut->clear();
  if (gather.empty()) return glm::vec3(0.0f);
  for (uint32_t root : tree_.roots) {
    SampleWords words;
    add(make_entry(gather, 0, root, nullptr, nullptr, words, stats, rays), words);
  }
  refine(gather, stats, rays);
  ++stats.cuts;
  stats.cut_nodes += cut_size_;
  stats.reconstructed += samples_.empty() ? 0 : 1;
  if (cut) {
    for (const Entry& e : entries_)
      if (e.alive) cut->push_back({e.light, e.visibility});
    std::sort(cut->begin(), cut->end(), [](const CutNode& a, const CutNode& b) { return a.light < b.light; });
  }
  return glm::vec3(total_);
}

bool CutEngine::shade_block(std::span<const GatherPoint> points, std::span<glm::vec3> out, CutStats& stats,
                            RayCounts& rays) {
  const size_t n = points.size();
  if (n == 0 || n > kMaxBlockPoints || out.size() < n) return false;
  float strength = 0.0f;
  for (const GatherPoint& g : points) {
    if (!g.valid() || g.surface.material->type != MaterialType::Diffuse || !same_surface(g, points[0])) return false;
    const float s = max_component(g.throughput);
    if (!(s > 0.0f)) return false;
    strength = std::max(strength, s);
  }
  block_gather_.build(points, 1, 0);  // its root: the box, cone and albedo of all the points
  block_entries_.clear();
  block_units_.clear();
  block_totals_.assign(n, glm::dvec3(0.0));
  heap_.clear();
  cut_size_ = 0;
  for (uint32_t root : tree_.roots) add_block_entry(points, strength, root, nullptr, stats, rays);
  while (!heap_.empty() && cut_size_ < size_t(settings_.max_cut)) {
    float smallest = INFINITY;
    for (const glm::dvec3& t : block_totals_) smallest = std::min(smallest, luminance(t));
    if (heap_.front().error <= settings_.error * smallest) break;
    const uint32_t worst = heap_.front().entry;
    std::pop_heap(heap_.begin(), heap_.end());
    heap_.pop_back();
    const BlockEntry parent = block_entries_[worst];
    if (parent.first != kNone) {
      const float scale = tree_.nodes[parent.light].weight_over_representative;
      for (size_t k = 0; k < n; ++k) block_totals_[k] -= glm::dvec3(block_units_[parent.first + k] * scale);
    }
    --cut_size_;
    add_block_entry(points, strength, parent.light + 1, &parent, stats, rays);
    add_block_entry(points, strength, tree_.nodes[parent.light].right, &parent, stats, rays);
  }
  for (size_t k = 0; k < n; ++k) out[k] = glm::vec3(block_totals_[k]);
  stats.cuts += n;
  stats.cut_nodes += cut_size_ * n;
  stats.blocked += n;
  return true;
}

// One node of a block cut: its bound over all the points, and each point's
// estimate (the parent's shadow rays where the representative is the same).
void CutEngine::add_block_entry(std::span<const GatherPoint> points, float strength, uint32_t light,
                                const BlockEntry* parent, CutStats& stats, RayCounts& rays) {
  const size_t n = points.size();
  const LightNode& ln = tree_.nodes[light];
  BlockEntry e;
  e.light = light;
  const uint32_t representative = ln.representative;
  float scale = 1.0f;  // a leaf is exact
  if (!ln.is_leaf()) {
    const glm::vec3 bound = pair_bound(block_gather_, 0, ln, lighting_.clamp_bound, strength);
    if (!(bound.x > 0.0f || bound.y > 0.0f || bound.z > 0.0f)) {  // nothing can arrive at any point
      e.first = kNone;
      block_entries_.push_back(e);
      ++cut_size_;
      return;
    }
    scale = ln.weight_over_representative;
    e.error = luminance(bound);
  }
  e.first = uint32_t(block_units_.size());
  block_units_.resize(block_units_.size() + n, glm::vec3(0.0f));
  if (parent && tree_.nodes[parent->light].representative == representative && parent->first != kNone) {
    std::copy_n(block_units_.begin() + parent->first, n, block_units_.begin() + e.first);
    stats.reused += n;
  } else {
    // The points' shadow rays towards the one leaf, in packets of 16 in
    // point order: a packet's rays depend on the block alone.
    const LightLeaf& leaf = tree_.leaves[representative];
    Ray shadow[16];
    glm::vec3 lit[16];
    uint32_t index[16];
    bool occluded[16];
    size_t count = 0;
    auto trace = [&] {
      accel_.occluded16({shadow, count}, {occluded, count});
      for (size_t i = 0; i < count; ++i)
        if (!occluded[i]) block_units_[e.first + index[i]] = lit[i];
      rays.shadow += count;
      count = 0;
    };
    for (size_t k = 0; k < n; ++k) {
      const glm::vec3 c = light_contribution(lighting_, points[k], leaf, shadow[count]);
      if (!(c.x + c.y + c.z > 0.0f)) continue;
      lit[count] = c * points[k].throughput;
      index[count++] = uint32_t(k);
      if (count == 16) trace();
    }
    if (count > 0) trace();
  }
  for (size_t k = 0; k < n; ++k) block_totals_[k] += glm::dvec3(block_units_[e.first + k] * scale);
  block_entries_.push_back(e);
  ++cut_size_;
  if (e.error > 0.0f) {
    heap_.push_back({e.error, uint32_t(block_entries_.size() - 1)});
    std::push_heap(heap_.begin(), heap_.end());
  }
}

}  // namespace igi::lightcuts
