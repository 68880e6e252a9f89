#pragma once
// A complete single-process render of one image: progressive passes of a
// method, accumulated. pt passes take consecutive sample indices (the union
// is one sample sequence); ir/igi passes advance the VPL seed.
#include <functional>

#include "core/method.h"
#include "render/frame_renderer.h"

namespace igi {

struct OfflineResult {
  Image image;
  RayCounts rays;
  double seconds = 0.0;
};

// `samples`: pt samples per pixel, or ir/igi passes. progress gets [0,1].
OfflineResult render_offline(const SceneContext& context, const RenderSettings& settings,
                             const FrameSetup& frame, int samples, const FrameOptions& options);

}  // namespace igi
