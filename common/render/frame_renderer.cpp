#include "render/frame_renderer.h"

#include <algorithm>
#include <atomic>
#include <chrono>
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
  std::atomic<size_t> next{0}, done{0};
  std::mutex rays_mutex;
  auto work = [&] {
    enable_flush_to_zero();
    RayCounts local;
    std::vector<glm::vec3> pixels;
    for (size_t i; (i = next.fetch_add(1)) < tiles.size();) {
      const TileJob& t = tiles[i];
      pixels.assign(size_t(t.w) * t.h, glm::vec3(0.0f));
      method.render_tile(t, pixels, local);
      for (int y = 0; y < t.h; ++y)
        std::copy_n(pixels.begin() + size_t(y) * t.w, t.w, image.pixels.begin() + size_t(t.y + y) * frame.width + t.x);
      done.fetch_add(1);
    }
    std::lock_guard lock(rays_mutex);
    rays += local;
  };
  const int threads = options.threads > 0 ? options.threads : default_thread_count();
  std::vector<std::thread> pool;
  for (int i = 1; i < threads; ++i) pool.emplace_back(work);
  if (options.progress) {
    // The caller's thread reports progress and then joins in with the work.
    std::thread reporter(work);
    while (done.load() < tiles.size()) {
      options.progress(float(done.load()) / float(tiles.size()));
      std::this_thread::sleep_for(std::chrono::milliseconds(250));
    }
    reporter.join();
    options.progress(1.0f);
  } else {
    work();
  }
  for (std::thread& t : pool) t.join();
  return image;
}

}  // namespace igi
