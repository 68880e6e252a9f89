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

}  // namespace igi::lightcuts
