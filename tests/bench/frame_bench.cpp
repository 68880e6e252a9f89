// igi-frame-bench: render_frame's tiles on TBB's threads against the code it
// replaced (threads spawned and joined on every pass, pulling tiles from an
// atomic counter; kept here as the baseline). Prints figures; asserts nothing
// but that both give the same pixels.
//
//   igi-frame-bench [frames] [threads]   (default 21 frames, all hardware threads)
//
// IGI on the Cornell box at two sizes: 320x240, and 96x72, where a frame
// takes a few milliseconds and starting threads counts. The two ways
// alternate frame by frame so load from other processes falls on both
// alike; every figure is the median, with the CPU time the process received.
#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <thread>
#include <vector>

#include "bench/bench_clock.h"
#include "methods/vpl_method.h"
#include "render/frame_renderer.h"
#include "scene/builtin_scenes.h"
#include "scene/accel.h"

namespace igi {
namespace {

using bench::Clock;
using bench::median;

// The baseline: what render_frame did before TBB.
Image render_frame_spawning(const Method& method, const FrameSetup& frame, int border, int tile_size, int threads,
                            RayCounts& rays) {
  Image image(frame.width, frame.height);
  const std::vector<TileJob> tiles = make_tiles(frame.width, frame.height, tile_size, tile_size, border);
  std::atomic<size_t> next{0};
  std::vector<RayCounts> counts(static_cast<size_t>(threads));
  auto work = [&](RayCounts& local) {
    enable_flush_to_zero();
    std::vector<glm::vec3> pixels;
    for (size_t i; (i = next.fetch_add(1)) < tiles.size();) {
      const TileJob& t = tiles[i];
      pixels.assign(size_t(t.w) * t.h, glm::vec3(0.0f));
      method.render_tile(t, pixels, local);
      image.paste(pixels, t.x, t.y, t.w, t.h);
    }
  };
  std::vector<std::thread> pool;
  for (int i = 1; i < threads; ++i) pool.emplace_back(work, std::ref(counts[size_t(i)]));
  work(counts[0]);
  for (std::thread& t : pool) t.join();
  for (const RayCounts& c : counts) rays += c;
  return image;
}

struct Times {
  std::vector<double> wall, cpu;
  void add(const Clock& d) { wall.push_back(d.wall); cpu.push_back(d.cpu); }
};

void bench_size(Method& method, int width, int height, int border, int frames, int threads) {
  FrameSetup frame;
  frame.camera = make_cornell_box().camera_or_auto();
  frame.width = width;
  frame.height = height;
  frame.seed = 1;
  method.begin_frame(frame);
  FrameOptions options;
  options.threads = threads;
  options.tile_size = 32;
  Times before, after;
  bool same = true;
  for (int f = 0; f < frames; ++f) {
    RayCounts a, b;
    Clock start = Clock::now();
    const Image old_way = render_frame_spawning(method, frame, border, options.tile_size, threads, a);
    before.add(Clock::now() - start);
    start = Clock::now();
    const Image new_way = render_frame(method, frame, border, options, b);
    after.add(Clock::now() - start);
    same = same && a.total() == b.total() &&
           std::memcmp(old_way.pixels.data(), new_way.pixels.data(), old_way.pixels.size() * sizeof(glm::vec3)) == 0;
  }
  const double bw = median(before.wall), aw = median(after.wall);
  std::printf("%4dx%-4d | %9.2f %9.2f | %9.2f %9.2f | %6.3f | %s\n", width, height, 1e3 * bw, 1e3 * median(before.cpu),
              1e3 * aw, 1e3 * median(after.cpu), aw / bw, same ? "identical" : "DIFFERENT PIXELS");
}

}  // namespace
}  // namespace igi

int main(int argc, char** argv) {
  using namespace igi;
  const int frames = argc > 1 ? std::max(1, std::atoi(argv[1])) : 21;
  const int threads = argc > 2 ? std::max(1, std::atoi(argv[2])) : default_thread_count();
  const Scene scene = make_cornell_box();
  const Accel accel(scene);
  const LightSet lights(scene);
  RenderSettings settings;
  settings.method = MethodKind::Igi;
  settings.paths_per_set = 8;
  VplMethod method({scene, accel, lights}, settings);
  std::printf("igi, Cornell box, %d VPL paths a set, %d threads, 32x32 tiles, median of %d frames, ms a frame\n",
              settings.paths_per_set, threads, frames);
  std::printf("%9s | %19s | %19s | %6s |\n", "", "spawned threads", "TBB", "ratio");
  std::printf("%9s | %9s %9s | %9s %9s | %6s |\n", "size", "wall", "cpu", "wall", "cpu", "wall");
  for (const auto& [w, h] : {std::pair{320, 240}, std::pair{96, 72}})
    bench_size(method, w, h, tile_border(settings), frames, threads);
  return 0;
}
