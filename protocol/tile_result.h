#pragma once
// A rendered tile made sendable: the TileResult a worker sends, and the
// master's own for a job no worker's result passed (render/frame_job.h
// renders both alike). The pixels go in `format` (wire_pixels: a non-finite
// pixel is sent as black and counted, as the master rejects them).
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/frame.h"
#include "protocol/messages.h"

namespace igi::protocol {

// render_seconds is left to the caller.
TileResult make_tile_result(uint64_t frame_id, uint64_t job_id, const TileJob& tile, std::vector<glm::vec3> pixels,
                            std::vector<PixelSurface> surfaces, const RayCounts& rays, uint64_t frame_state_hash,
                            PixelFormat format);

}  // namespace igi::protocol
