#pragma once
// What frame i of an igi-master run is: its camera (along --camera-path),
// seed, samples and sub-pixel position. One function, so that a test can
// render the very same frames in one process (tests/soak).
#include <string>

#include "render/frame.h"
#include "render_options.h"
#include "scene/scene.h"

namespace igi {

// camera_path: "" (the scene's camera) or "orbit" (a turn of 0.02 rad a frame
// about the vertical axis through the scene's centre). progressive: frame i > 0
// is a new estimate (seed + i, a new jitter; pt continues the sample sequence).
FrameSetup plan_frame(const RenderOptions& render, const std::string& camera_path, const Scene& scene, int i,
                      bool progressive);

}  // namespace igi
