// igi-view-history-bench: what the window's thread spends on each frame it
// shows while the camera moves (render/view_history.h): ViewHistory::add
// (the frame's surfaces, the history carried into its view) and resolve()
// with weight() (the image uploaded, the status line), at the window's
// default 640x480, for full frames and 1/5 previews. A plane faces the
// camera, which turns a little each frame, so most pixels carry. Prints
// medians of wall and CPU time; asserts nothing.
//
//   igi-view-history-bench [width height] [frames]   (default 640 480, 21 frames)
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "bench/bench_clock.h"
#include "render/view_history.h"

namespace igi {
namespace {

int run(int width, int height, int frames) {
  ViewHistory history(width, height, 16);
  Camera camera;
  camera.position = {0.0f, 1.0f, 4.0f};
  camera.forward = {0.0f, 0.0f, -1.0f};
  camera.up = {0.0f, 1.0f, 0.0f};
  auto frame_of = [&](int d) {
    Image image(width / d, height / d);
    for (glm::vec3& p : image.pixels) p = glm::vec3(0.5f);
    return image;
  };
  auto surfaces_of = [&](int d) {  // a wall facing the camera, 4 units away
    std::vector<PixelSurface> s(size_t(width / d) * size_t(height / d));
    for (PixelSurface& p : s) p.depth = 4.0f, p.normal[2] = 127;
    return s;
  };
  history.add(frame_of(1), surfaces_of(1), camera, 1.0);
  std::printf("%dx%d, the camera turning 0.3 degrees a frame, median of %d frames (wall ms, CPU ms):\n", width, height,
              frames);
  int turn = 0;
  for (int d : {1, 5}) {
    const Image frame = frame_of(d);
    const std::vector<PixelSurface> surfaces = surfaces_of(d);
    std::vector<double> add_wall, add_cpu, show_wall, show_cpu;
    for (int i = 0; i < frames; ++i) {
      camera.forward = glm::normalize(glm::vec3(0.005f * float(++turn), 0.0f, -1.0f));
      const bench::Clock t0 = bench::Clock::now();
      history.add(frame, surfaces, camera, d == 1 ? 1.0 : 1.0 / (d * d));
      const bench::Clock t1 = bench::Clock::now();
      const Image shown = history.resolve();
      const double weight = history.weight();
      const bench::Clock t2 = bench::Clock::now();
      if (shown.pixels.empty() || weight < 0.0) return 1;
      add_wall.push_back(1e3 * (t1 - t0).wall), add_cpu.push_back(1e3 * (t1 - t0).cpu);
      show_wall.push_back(1e3 * (t2 - t1).wall), show_cpu.push_back(1e3 * (t2 - t1).cpu);
    }
    std::printf("  %-12s add %6.1f (%6.1f)   resolve + weight %5.1f (%5.1f)   carried %.0f %%\n",
                d == 1 ? "full frames" : "1/5 previews", bench::median(add_wall), bench::median(add_cpu),
                bench::median(show_wall), bench::median(show_cpu), 100.0 * history.carried());
  }
  return 0;
}

}  // namespace
}  // namespace igi

int main(int argc, char** argv) {
  const int width = argc > 2 ? std::atoi(argv[1]) : 640, height = argc > 2 ? std::atoi(argv[2]) : 480;
  const int frames = argc > 3 ? std::atoi(argv[3]) : 21;
  return igi::run(width, height, frames);
}
