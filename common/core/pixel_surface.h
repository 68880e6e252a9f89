#pragma once
// The surfaces a frame's pixels show, for the master's reprojection
// (render/view_history.h): one camera ray through each pixel's centre, the
// same ray in every tile, thread and worker (core/camera_front_end.h).
#include <span>

#include "core/frame.h"
#include "scene/accel.h"
#include "scene/surface.h"

namespace igi {

// Whether a surface point's colour changes with the view too much for its
// history to be carried to another (PixelSurface::kViewDependent): mirrors,
// glass and GGX lobes (metal, glTF's coat) of alpha below kViewDependentAlpha.
// A wider lobe's reflection turns with the view more slowly than a drag's
// carried history refreshes (30 degrees a second, frames every 50 ms, a
// history of 16 frames lags about 24 degrees, 0.4 rad): Sponza's stone
// (roughness 0.9-1, alpha 0.8-1) carries, BreakfastRoom's varnish (roughness
// 0.2-0.4) does not. Before, every non-Lambert surface counted as
// view-dependent, so no pixel of a glTF file's metallic-roughness scene ever
// carried its history while the camera moved.
inline constexpr float kViewDependentAlpha = 0.5f;
bool view_dependent(const SurfacePoint& sp);

// `out`: tile.w * tile.h surfaces of the tile's interior (not its border),
// row-major. Returns the rays traced (one a pixel).
uint64_t trace_pixel_surfaces(const Accel& accel, const FrameSetup& frame, const TileJob& tile,
                              std::span<PixelSurface> out);

}  // namespace igi
