#include "protocol/tile_result.h"

#include <utility>

#include "protocol/pixels.h"

namespace igi::protocol {

TileResult make_tile_result(uint64_t frame_id, uint64_t job_id, const TileJob& tile, std::vector<glm::vec3> pixels,
                            std::vector<PixelSurface> surfaces, const RayCounts& rays, uint64_t frame_state_hash,
                            PixelFormat format) {
  TileResult r;
  r.frame_id = frame_id;
  r.job_id = job_id;
  r.tile = tile;
  r.pixels = std::move(pixels);
  r.rays = rays;
  r.surfaces = std::move(surfaces);
  r.pixel_format = format;
  r.nonfinite_pixels = wire_pixels(r.pixels, format);  // the master rejects non-finite pixels
  r.frame_state_hash = frame_state_hash;
  return r;
}

}  // namespace igi::protocol
