#pragma once
// A complete single-process render of one image: progressive passes of a
// method, accumulated. pt passes take consecutive sample indices (the union
// is one sample sequence); ir/igi passes advance the VPL seed.
#include <atomic>
#include <functional>

#include "core/method.h"
#include "render/frame_renderer.h"

namespace igi {

struct OfflineResult {
  Image image;         // empty when stopped before the first pass finished
  RayCounts rays;
  double seconds = 0.0;
  int passes = 0;      // passes accumulated
  int planned = 0;     // passes asked for: passes < planned when stopped
};

// `samples`: pt samples per pixel, or ir/igi passes. progress gets [0,1].
// `stop` (a Ctrl-C): checked between passes; the passes done so far are the result.
OfflineResult render_offline(const SceneContext& context, const RenderSettings& settings,
                             const FrameSetup& frame, int samples, const FrameOptions& options,
                             const std::atomic<bool>* stop = nullptr);

}  // namespace igi
