#include "render/frame_renderer.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <optional>
#include <thread>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "core/parallel.h"
#include "scene/accel.h"

namespace igi {

int default_thread_count() { return std::max(1u, std::thread::hardware_concurrency()); }

namespace {

// Reports progress from the calling thread at most every 250 ms, while that
// thread renders tiles like any other.
class ProgressReporter {
 public:
  ProgressReporter(const std::function<void(float)>& report, size_t tiles)
      : report_(report), tiles_(tiles), caller_(std::this_thread::get_id()), last_(Clock::now()) {}
  void tile_done() {
    const size_t done = done_.fetch_add(1) + 1;
    if (!report_ || std::this_thread::get_id() != caller_) return;
    const Clock::time_point now = Clock::now();
    if (now - last_ < std::chrono::milliseconds(250)) return;
    last_ = now;
    report_(float(done) / float(tiles_));
  }

 private:
  using Clock = std::chrono::steady_clock;
  const std::function<void(float)>& report_;
  const size_t tiles_;
  const std::thread::id caller_;
  Clock::time_point last_;  // read and written by the caller's thread only
  std::atomic<size_t> done_{0};
};

}  // namespace

namespace {

// The frame's tiles on TBB's threads, each rendered by `render_tile(tile, pixels, rays)`.
template <class RenderTile>
Image render_tiles(const FrameSetup& frame, int border, const FrameOptions& options, RayCounts& rays,
                   const RenderTile& render_tile) {
  Image image(frame.width, frame.height);
  const std::vector<TileJob> tiles = make_tiles(frame.width, frame.height, options.tile_size, options.tile_size, border);
  tbb::enumerable_thread_specific<RayCounts> counts;
  ProgressReporter progress(options.progress, tiles.size());
  // One tile a task: tiles are large units of work, and each lands in its own
  // rectangle of the image, so the frame does not depend on which thread
  // rendered what, nor on the thread count.
  auto render_tiles = [&](const tbb::blocked_range<size_t>& range) {
    FlushToZeroScope flush_to_zero;
    RayCounts& local = counts.local();
    std::vector<glm::vec3> pixels;
    for (size_t i = range.begin(); i < range.end(); ++i) {
      const TileJob& t = tiles[i];
      pixels.assign(size_t(t.w) * t.h, glm::vec3(0.0f));
      render_tile(t, std::span<glm::vec3>(pixels), local);
      image.paste(pixels, t.x, t.y, t.w, t.h);
      progress.tile_done();
    }
  };
  const int threads = options.threads > 0 ? options.threads : default_thread_count();
  // TBB keeps one thread a core unless told otherwise; more threads than
  // cores, when asked for, are allowed for this frame (never fewer for
  // others: a lower limit would hold back Embree's builds elsewhere).
  std::optional<tbb::global_control> allow_more;
  if (threads > tbb::info::default_concurrency())
    allow_more.emplace(tbb::global_control::max_allowed_parallelism, size_t(threads));
  tbb::task_arena arena(threads);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, tiles.size(), 1), render_tiles, tbb::simple_partitioner());
  });
  for (const RayCounts& c : counts) rays += c;
  if (options.progress) options.progress(1.0f);
  return image;
}

}  // namespace

Image render_frame(const Method& method, const FrameSetup& frame, int border, const FrameOptions& options,
                   RayCounts& rays) {
  return render_tiles(frame, border, options, rays, [&](const TileJob& t, std::span<glm::vec3> p, RayCounts& r) {
    method.render_tile(t, p, r);
  });
}

Image render_frame(const FrameJob& job, const FrameOptions& options, RayCounts& rays) {
  return render_tiles(job.frame(), job.border(), options, rays,
                      [&](const TileJob& t, std::span<glm::vec3> p, RayCounts& r) { job.render_pixels(t, p, r); });
}

}  // namespace igi
