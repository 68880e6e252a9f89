#pragma once
// A frame's jobs as a node renders them. igi-worker's render pool, the
// master's own tiles and hashes (master/trust/master_renderer.h) and
// igi-render (render/offline_render.h) all render this way, so a tile is the
// same pixels, surfaces and hash whoever renders it.
//
// Call order: construct (the method is made for the settings; it throws
// std::invalid_argument for settings it cannot render), begin() with the
// scene standing at the frame's pose (the VPL sets, light tree and photon
// map: single-threaded here, parallel inside on the shared TBB pool), then
// render() any tile of that frame from any number of threads at once, and
// state_hash(). begin() again for another frame of the same settings (a pass).
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "core/frame.h"
#include "core/method.h"
#include "core/tiling.h"

namespace igi {

// A tile's pixels and, where its frame wants them, their surfaces.
struct RenderedTile {
  std::vector<glm::vec3> pixels;       // tile.w x tile.h linear RGB, row-major
  std::vector<PixelSurface> surfaces;  // as many when the frame wants them (the master's reprojection), else none
  RayCounts rays;                      // the surfaces' camera rays counted with the camera's
};

class FrameJob {
 public:
  FrameJob(const SceneContext& context, const RenderSettings& settings);
  void begin(const FrameSetup& frame);
  RenderedTile render(const TileJob& tile) const;
  // The pixels alone, into `pixels` (tile.w x tile.h): what render() makes of them.
  void render_pixels(const TileJob& tile, std::span<glm::vec3> pixels, RayCounts& rays) const;
  uint64_t state_hash() const { return method_->frame_state_hash(); }  // the VPL sets (and tree, photons)
  const FrameSetup& frame() const { return frame_; }
  const RenderSettings& settings() const { return settings_; }
  int border() const { return tile_border(settings_); }

 private:
  const Accel& accel_;
  RenderSettings settings_;
  std::unique_ptr<Method> method_;
  FrameSetup frame_;
};

}  // namespace igi
