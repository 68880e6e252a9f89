#pragma once
// What frame i of an igi-master run is: its camera (along --camera-path),
// seed, samples and sub-pixel position. One function, so that a test can
// render the very same frames in one process (tests/soak).
#include <string>

#include "render/frame.h"
#include "render_options.h"
#include "scene/scene.h"

namespace igi {

// camera_path: "" (the scene's camera, where an animated camera stands at
// the frame's time) or "orbit" (a turn of 0.02 rad a frame
// about the vertical axis through the scene's centre). progressive: frame i is
// pass i of one estimate, exactly as igi-render's passes: ir/igi take seed + i
// and sub-pixel position sample_2d(i, 0, seed) (pass 0 included, so the
// positions are one stratified set); pt keeps the seed and takes samples
// [i x spp, (i + 1) x spp) of its sequence. An animated scene's frame i
// stands at render.time + i x render.time_step (wrapped with render.loop),
// and is never progressive: every frame is a whole estimate of its own time.
FrameSetup plan_frame(const RenderOptions& render, const std::string& camera_path, const Scene& scene, int i,
                      bool progressive);

}  // namespace igi
