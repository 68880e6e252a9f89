#pragma once
// Renders a whole frame in one process: cuts it into tiles and renders them
// on TBB's threads (a task arena of the requested size, the calling thread
// one of them). The distributed master uses the same TileJob list.
#include <functional>
#include <vector>

#include "core/method.h"
#include "core/tiling.h"
#include "render/frame_job.h"
#include "image/image.h"

namespace igi {

struct FrameOptions {
  int tile_size = 32;
  int threads = 0;  // 0: all hardware threads
  // Called from the calling thread, between the tiles it renders, at most
  // every 250 ms, with the fraction of tiles done; last with 1.
  std::function<void(float)> progress;
};

// The frame `job` has begun, whole (render/frame_job.h: as a worker renders its tiles).
Image render_frame(const FrameJob& job, const FrameOptions& options, RayCounts& rays);
// The same with a Method that has begun `frame` (benchmarks and tests that hold a method).
Image render_frame(const Method& method, const FrameSetup& frame, int border,
                   const FrameOptions& options, RayCounts& rays);

int default_thread_count();

}  // namespace igi
