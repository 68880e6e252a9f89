#include "protocol/tile_render.h"

#include "core/pixel_surface.h"
#include "protocol/pixels.h"

namespace igi::protocol {

TileResult render_tile_result(const Method& method, const Accel& accel, const FrameSetup& frame, uint64_t job_id,
                              const TileJob& tile, PixelFormat format) {
  TileResult r;
  r.frame_id = frame.frame_id;
  r.job_id = job_id;
  r.tile = tile;
  r.pixels.resize(size_t(tile.w) * size_t(tile.h));
  method.render_tile(tile, r.pixels, r.rays);
  if (frame.want_surfaces) {  // the master's reprojection; its rays are counted with the camera's
    r.surfaces.resize(r.pixels.size());
    r.rays.primary += trace_pixel_surfaces(accel, frame, tile, r.surfaces);
  }
  r.pixel_format = format;
  r.nonfinite_pixels = wire_pixels(r.pixels, format);  // the master rejects non-finite pixels
  r.frame_state_hash = method.frame_state_hash();
  return r;
}

}  // namespace igi::protocol
