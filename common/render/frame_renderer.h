#pragma once
// Renders a whole frame in one process: cuts it into tiles and renders them
// on TBB's threads (a task arena of the requested size, the calling thread
// one of them). The distributed master uses the same TileJob list.
#include <functional>
#include <vector>

#include "core/method.h"
#include "image/image.h"

namespace igi {

// Tiles of at most tile_w x tile_h covering the image, each with `border`,
// ordered in a spiral from the centre so the image fills in evenly.
std::vector<TileJob> make_tiles(int width, int height, int tile_w, int tile_h, int border);

struct FrameOptions {
  int tile_size = 32;
  int threads = 0;  // 0: all hardware threads
  // Called from the calling thread, between the tiles it renders, at most
  // every 250 ms, with the fraction of tiles done; last with 1.
  std::function<void(float)> progress;
};

// begin_frame() must already have been called on `method`.
Image render_frame(const Method& method, const FrameSetup& frame, int border,
                   const FrameOptions& options, RayCounts& rays);

int default_thread_count();

}  // namespace igi
