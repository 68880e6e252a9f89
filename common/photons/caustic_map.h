#pragma once
// The caustic photon map of one frame, and its density estimate.
//
// build() traces the frame's photon paths (photon_paths.h) and grids them
// (photon_grid.h); it is a pure function of scene, settings and seed, and
// its content hash joins the VPL sets' in the method's frame_state_hash, so
// the master sees a worker whose map differs. Replicated, not partitioned:
// every worker traces all the paths (no communication, no barrier; the
// cost is paid once per worker, which is why the path count is modest and
// progressive passes add fresh photons instead).
//
// radiance() is the demodulated estimate at a G-buffer sample (the BSDF
// with albedo 1, as the VPL sums), towards the viewer:
//   L(x, wo) = sum_p f(x, wo, wi_p) flux_p K(|x - x_p|),
//   K(d) = 3 / (pi r^2) (1 - d^2 / r^2)^2,
// the Silverman-type kernel of pbrt-v2's photon map (it integrates to 1
// over the disc of radius r and falls smoothly to 0 at its edge), with two
// radii: r (--caustic-radius) for photons straight from an emitter through
// mirrors and glass (L S+ D, the focused caustics), and kBouncedRadiusScale
// x r for photons whose path bounced off a diffuse or glossy surface first
// (L (D|G)+ S+ D: indirect light passed on by a mirror or glass, as smooth as
// any indirect light, and sparse: at one radius for both it speckles every
// wall the mirror faces). Each set is split again by density: a photon with
// fewer than kDenseNeighbours photons of its set within its radius (itself
// included) is sparse, and sparse photons of either set are gathered at a
// wider radius, sparse_radius_scale(pass) r: 4 r at one pass, relaxing to
// 2 r as passes accumulate. Light that glass or a mirror spreads thin (the
// glass ball's reflection of the lamp over the ceiling and walls) otherwise
// shows as a speckle a photon at one pass (glass scene, 128x128, against
// pt: FLIP 0.097 -> 0.092 at one pass), while dense, focused caustics keep
// their radius and their edges. Each kernel integrates to 1, so the splits
// move no energy, they only blur the smooth and the sparse parts more. Only
// photons on the viewer's side of a surface facing the same way count
// (normals within kNormalCos), so light does not leak through thin walls or
// round corners; near such edges the disc is partly empty and the estimate
// darkens (boundary bias, as any fixed-radius estimate).
//
// Every radius shrinks with the progressive pass as progressive photon
// mapping's does (Hachisuka, Ogaki, Jensen 2008; each pass an independent
// estimate, as in Knaus and Zwicker 2011): r_k = ppm_radius_scale(k) r, with
// r_k^2 = r^2 prod_{j=1..k} (j + alpha) / (j + 1), alpha = 2/3. The blur
// (bias ~ r_k^2 ~ k^(alpha - 1)) vanishes while each pass's variance grows
// only as k^(1 - alpha), so the mean of the passes converges to the caustic
// itself. A frame that starts the accumulation (pass 0: every moving view)
// keeps r.
//
// Thread-safety: build() single caller; radiance() const, any threads.
#include <cstdint>
#include <vector>

#include "core/gbuffer.h"
#include "core/method.h"
#include "photons/photon_grid.h"

namespace igi {

class CausticMap {
 public:
  static constexpr float kNormalCos = 0.9f;
  static constexpr float kBouncedRadiusScale = 2.0f;
  static constexpr int kDenseNeighbours = 8;      // photons within the radius, itself included
  static constexpr float kSparseRadiusScale = 4.0f;  // sparse photons' radius over r at one pass
  static constexpr double kPpmAlpha = 2.0 / 3.0;     // the fraction of photons a pass keeps (PPM's alpha)

  CausticMap(const SceneContext& context, const RenderSettings& settings);

  // `threads` trace the paths (0: all hardware threads); the map does not
  // depend on it. `pass`: the progressive pass (0-based), which sets the
  // radii (ppm_radius_scale, sparse_radius_scale).
  void build(uint32_t frame_seed, int threads = 0, uint32_t pass = 0);
  glm::vec3 radiance(const GSample& g) const;

  uint64_t hash() const { return hash_; }
  uint32_t paths() const { return paths_; }
  size_t photon_count() const { return focused_.size() + bounced_.size() + sparse_.size(); }
  float radius() const { return radius_; }  // r, at pass 0
  // Rays traced by the last build().
  const RayCounts& rays() const { return rays_; }

 private:
  SceneContext context_;
  RenderSettings settings_;
  float radius_;      // absolute, in scene units
  uint32_t paths_;
  PhotonGrid focused_, bounced_;  // dense photons, Photon::bounced 0 and 1: radius r and kBouncedRadiusScale r
  PhotonGrid sparse_;  // the sparse photons of both, radius sparse_radius_scale(pass) r
  uint64_t hash_ = 0;
  RayCounts rays_;
};

uint64_t hash_photons(const std::vector<Photon>& photons);

// r_k / r at progressive pass k (0-based): sqrt(prod_{j=1..k} (j + alpha) /
// (j + 1)), about (0.90 k^(1/3))^(-1/2) for large k: 1 at pass 0, 0.67 at
// pass 15, 0.42 at pass 255.
float ppm_radius_scale(uint32_t pass);

// The sparse photons' radius over r_k at progressive pass k (0-based):
// kSparseRadiusScale / (k + 1)^(1/4), as the clamp relaxes (core/clamp.h),
// but never below kBouncedRadiusScale, so no sparse photon is gathered
// sharper than the dense ones of its set: 4 r at one pass, 2 r from pass 16 on.
float sparse_radius_scale(uint32_t pass);

// Photons with fewer than `min_neighbours` photons of `photons` within
// `radius` (themselves included) go to `sparse`, the others to `dense`, each
// in input order. The count is symmetric in the photons and does not depend
// on their order, so the split is as deterministic as the map.
void split_by_density(const std::vector<Photon>& photons, float radius, glm::vec3 origin, int min_neighbours,
                      std::vector<Photon>& dense, std::vector<Photon>& sparse);

}  // namespace igi
