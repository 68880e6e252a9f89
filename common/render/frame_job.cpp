#include "render/frame_job.h"

#include <stdexcept>
#include <string>

#include "core/pixel_surface.h"

namespace igi {

FrameJob::FrameJob(const SceneContext& context, const RenderSettings& settings)
    : accel_(context.accel), settings_(settings), method_(make_method(context, settings)) {
  if (!method_) throw std::invalid_argument(std::string("method not available: ") + method_name(settings.method));
}

void FrameJob::begin(const FrameSetup& frame) {
  frame_ = frame;
  method_->begin_frame(frame);
}

void FrameJob::render_pixels(const TileJob& tile, std::span<glm::vec3> pixels, RayCounts& rays) const {
  method_->render_tile(tile, pixels, rays);
}

RenderedTile FrameJob::render(const TileJob& tile) const {
  RenderedTile r;
  r.pixels.resize(size_t(tile.w) * size_t(tile.h));
  if (!frame_.want_surfaces) {
    render_pixels(tile, r.pixels, r.rays);
    return r;
  }
  // The master's reprojection: from the method's own camera rays, or a pass
  // of their own (counted with the camera's rays).
  r.surfaces.resize(r.pixels.size());
  if (!method_->render_tile_with_surfaces(tile, r.pixels, r.surfaces, r.rays)) {
    render_pixels(tile, r.pixels, r.rays);
    r.rays.primary += trace_pixel_surfaces(accel_, frame_, settings_.aa_samples, tile, r.surfaces);
  }
  return r;
}

}  // namespace igi
