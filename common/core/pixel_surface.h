#pragma once
// The surfaces a frame's pixels show, for the master's reprojection
// (render/view_history.h): one camera ray through each pixel's centre, the
// same ray in every tile, thread and worker (core/camera_front_end.h).
#include <span>

#include "core/frame.h"
#include "scene/accel.h"

namespace igi {

// `out`: tile.w * tile.h surfaces of the tile's interior (not its border),
// row-major. Returns the rays traced (one a pixel).
uint64_t trace_pixel_surfaces(const Accel& accel, const FrameSetup& frame, const TileJob& tile,
                              std::span<PixelSurface> out);

}  // namespace igi
