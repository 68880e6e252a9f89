#pragma once
// Method `lightcuts` (Walter, Fernandez, Arbree, Bala, Donikian and
// Greenberg, SIGGRAPH 2005), over the VPLs of ir: every Surface and Area VPL
// of all N x N sets, scaled by 1/S, plus the scene's point, spot and
// directional lights, exact, in one light tree (lightcuts/light_tree.h).
// Per pixel a cut through the tree with an error bound (lightcuts/cut.h);
// optionally reconstruction cuts on a sparse sample grid
// (lightcuts/reconstruction.h) or several gather points per pixel through
// the product of a gather tree and the light tree (multidimensional
// lightcuts, lightcuts/gather_tree.h). Plain cuts are taken by blocks of
// B x B pixels (--lightcuts-block) where a block lies on one Lambertian
// surface: one cut for the block, each pixel its own estimate over it.
//
// begin_frame generates the VPLs (vpl/vpl_generator.h, as ir does) and
// builds the tree: both are pure functions of scene, settings and seed, and
// both are hashed into frame_state_hash. render_tile is const and
// thread-safe; a pixel depends only on its global coordinates and the frame.
#include <atomic>
#include <memory>

#include "core/method.h"
#include "core/vpl.h"
#include "lightcuts/cut.h"
#include "lightcuts/light_tree.h"

namespace igi::lightcuts {

class LightcutsMethod final : public Method {
 public:
  // Throws std::invalid_argument for settings lightcuts cannot use.
  LightcutsMethod(const SceneContext& context, const RenderSettings& settings);
  void begin_frame(const FrameSetup& frame) override;
  void render_tile(const TileJob& job, std::span<glm::vec3> out, RayCounts& rays) const override;
  uint64_t frame_state_hash() const override { return state_hash_; }

  const VplSets& vpls() const { return vpls_; }
  const LightTree& tree() const { return tree_; }
  // Summed over the tiles rendered since begin_frame (benchmarks, tests).
  CutStats stats() const;

 private:
  CutEngine engine() const;
  void render_plain(const TileJob& job, std::span<glm::vec3> out, CutStats& stats, RayCounts& rays) const;
  void render_blocks(const TileJob& job, std::span<glm::vec3> out, CutStats& stats, RayCounts& rays) const;
  void render_reconstructed(const TileJob& job, std::span<glm::vec3> out, CutStats& stats, RayCounts& rays) const;

  SceneContext context_;
  RenderSettings settings_;
  FrameSetup frame_;
  VplSets vpls_;
  std::vector<Vpl> scene_lights_;  // the leaves of the scene's lights shade as these (core/direct_lights.h)
  LightTree tree_;
  float clamp_bound_ = INFINITY;
  uint64_t state_hash_ = 0;
  mutable std::atomic<uint64_t> cuts_{0}, cut_nodes_{0}, reused_{0}, interpolated_{0}, reconstructed_{0}, blocked_{0};
};

}  // namespace igi::lightcuts
