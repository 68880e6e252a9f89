#pragma once
// A tile job rendered into the result a worker sends. The worker's render
// pool and the master (which renders a job itself when no worker's result
// for it passes validation) both make results here, so the master's tile is
// the very one a worker would have sent, bit for bit.
#include <cstdint>

#include "core/frame.h"
#include "core/method.h"
#include "protocol/messages.h"
#include "scene/accel.h"

namespace igi::protocol {

// `method` has begun `frame` on `accel`'s scene at the frame's pose. The
// pixels are made sendable in `format` (wire_pixels: non-finite ones black),
// the frame's pixel surfaces traced when it wants them, and the method's
// VPL-set hash set. render_seconds is left to the caller.
TileResult render_tile_result(const Method& method, const Accel& accel, const FrameSetup& frame, uint64_t job_id,
                              const TileJob& tile, PixelFormat format);

}  // namespace igi::protocol
