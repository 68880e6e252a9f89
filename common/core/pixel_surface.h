#pragma once
// The surfaces a frame's pixels show, for the master's reprojection
// (render/view_history.h): the first hit of one camera ray a pixel, through
// sub-sample 0 of the frame's grid (surface_film_offset(): the ray the
// G-buffer traces first, core/gbuffer.h, so a method that traces it takes
// the surface from there instead of a pass of its own), the same ray in
// every tile, thread and worker (core/camera_front_end.h).
#include <span>

#include <glm/vec2.hpp>

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

// Where inside each pixel the surfaces' rays pass, in pixel units: sub-sample
// 0 of `samples_per_pixel` (the settings' aa_samples) at the frame's jitter.
glm::vec2 surface_film_offset(const FrameSetup& frame, int samples_per_pixel);

// What a camera ray along `direction` that hit `hit` shows.
PixelSurface pixel_surface(const Accel& accel, const Hit& hit, glm::vec3 direction);

// `out`: tile.w * tile.h surfaces of the tile's interior (not its border),
// row-major. Returns the rays traced (one a pixel).
uint64_t trace_pixel_surfaces(const Accel& accel, const FrameSetup& frame, int samples_per_pixel, const TileJob& tile,
                              std::span<PixelSurface> out);

}  // namespace igi
