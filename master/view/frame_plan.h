#pragma once
// What frame i of an igi-master run is: its camera (along --camera-path),
// seed, samples and sub-pixel position. One function, so that a test can
// render the very same frames in one process (tests/soak).
#include "core/frame.h"
#include "options/camera_path.h"
#include "options/render_options.h"
#include "scene/scene.h"

namespace igi {

// The angle of frame i along the path, in radians (0 for Kind::None).
double camera_path_angle(const CameraPath& path, int i);

// camera_path: as above. progressive: frame i is pass i of one estimate,
// exactly as igi-render's passes: ir/igi take seed + i
// and sub-pixel position sample_2d(i, 0, seed) (pass 0 included, so the
// positions are one stratified set); pt keeps the seed and takes samples
// [i x spp, (i + 1) x spp) of its sequence. An animated scene's frame i
// stands at render.time + i x render.time_step (wrapped with render.loop),
// and is never progressive: every frame is a whole estimate of its own time.
FrameSetup plan_frame(const RenderOptions& render, const CameraPath& camera_path, const Scene& scene, int i,
                      bool progressive);

}  // namespace igi
