#include "render/frame_renderer.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cmath>
#include <mutex>
#include <thread>

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

Image render_frame(const Method& method, const FrameSetup& frame, int border,
                   const FrameOptions& options, RayCounts& rays) {
  Image image(frame.width, frame.height);
  const std::vector<TileJob> tiles = make_tiles(frame.width, frame.height, options.tile_size, options.tile_size, border);
  std::atomic<size_t> next{0};
  size_t done = 0;  // guarded by mutex
  std::mutex mutex;
  std::condition_variable all_done;
  auto work = [&] {
    enable_flush_to_zero();
    RayCounts local;
    std::vector<glm::vec3> pixels;
    size_t finished = 0;
    for (size_t i; (i = next.fetch_add(1)) < tiles.size(); ++finished) {
      const TileJob& t = tiles[i];
      pixels.assign(size_t(t.w) * t.h, glm::vec3(0.0f));
      method.render_tile(t, pixels, local);
      image.paste(pixels, t.x, t.y, t.w, t.h);
    }
    std::lock_guard lock(mutex);
    rays += local;
    done += finished;
    if (done == tiles.size()) all_done.notify_all();
  };
  const int threads = options.threads > 0 ? options.threads : default_thread_count();
  std::vector<std::thread> pool;
  for (int i = 1; i < threads; ++i) pool.emplace_back(work);
  if (options.progress) {
    // The caller's thread reports progress while `threads` others work. It
    // wakes when the last tile is done, not at its next report: a frame
    // shorter than the report interval costs nothing extra.
    pool.emplace_back(work);
    std::unique_lock lock(mutex);
    while (!all_done.wait_for(lock, std::chrono::milliseconds(250), [&] { return done == tiles.size(); })) {
      const size_t claimed = std::min(next.load(), tiles.size());
      lock.unlock();
      options.progress(float(claimed) / float(tiles.size()));
      lock.lock();
    }
    lock.unlock();
    options.progress(1.0f);
  } else {
    work();
  }
  for (std::thread& t : pool) t.join();
  return image;
}

}  // namespace igi
