#pragma once
// Stochastic VPL selection for ir and igi (--vpl-draws K), after stochastic
// lightcuts (Yuksel, HPG 2019). Instead of the VPLs of its interleaved set,
// each shading point (every sub-sample of every pixel, every glossy gather
// hit) draws K VPLs of all S = N x N sets from a light tree over them
// (lightcuts/light_tree.h), each with the probability p that the tree's
// cluster bounds give it at that point (lightcuts/light_sampler.h), and adds
// each one's light (VplShading::contribution, one shadow ray) / (K p S).
// The mean is ir's sum over all sets / S, the light each set alone
// estimates, but from all S sets' VPLs at the shadow rays of K: one set's
// blotches (the same few VPLs behind every pixel of the set) become fine
// per-point noise, which the discontinuity buffer and the wavelet filter
// average over neighbours' independent draws. The scene's point, spot and
// directional lights stay exact (core/direct_lights.h); the tree holds
// the VPLs alone.
//
// Determinism: the tree is a pure function of the VPLs and the frame seed;
// a point's draws take their u from a Sobol stream seeded by the frame seed,
// the point's global pixel, its G-buffer layer and (gather hits) its rank
// among its owner's hits. Nothing depends on the tile.
#include <cstdint>
#include <span>

#include <glm/vec3.hpp>

#include "core/frame.h"
#include "core/gbuffer.h"
#include "core/vpl.h"
#include "core/vpl_contribution.h"
#include "lightcuts/light_tree.h"
#include "scene/accel.h"

namespace igi {

class VplDraws {
 public:
  VplDraws(const Scene& scene, const VplSets& vpls, uint32_t frame_seed);
  uint64_t hash() const { return tree_.hash; }
  const lightcuts::LightTree& tree() const { return tree_; }

  // The demodulated VPL light at g (as VplShading::contribution sums it) from
  // `draws` draws of the stream `seed`.
  glm::vec3 shade(const GSample& g, int draws, uint32_t seed, std::span<const Vpl> vpls, const VplShading& shading,
                  const Accel& accel, RayCounts& rays) const;

 private:
  lightcuts::LightTree tree_;
  float min_distance2_ = 0.0f;
  float inv_sets_ = 1.0f;
};

}  // namespace igi
