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

std::vector<TileJob> make_tiles(int width, int height, int tile_w, int tile_h, int border) {
  std::vector<TileJob> tiles;
  for (int y = 0; y < height; y += tile_h)
    for (int x = 0; x < width; x += tile_w)
      tiles.push_back({x, y, std::min(tile_w, width - x), std::min(tile_h, height - y), border});
  // Spiral from the centre: order by distance to it, ties by angle (stable).
  const float cx = 0.5f * width, cy = 0.5f * height;
  auto key = [&](const TileJob& t) {
    float dx = t.x + 0.5f * t.w - cx, dy = t.y + 0.5f * t.h - cy;
    return std::make_pair(std::max(std::abs(dx) / tile_w, std::abs(dy) / tile_h), std::atan2(dy, dx));
  };
  std::stable_sort(tiles.begin(), tiles.end(), [&](const TileJob& a, const TileJob& b) { return key(a) < key(b); });
  return tiles;
}

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

Image render_frame(const Method& method, const FrameSetup& frame, int border,
                   const FrameOptions& options, RayCounts& rays) {
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
      method.render_tile(t, pixels, local);
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

}  // namespace igi
