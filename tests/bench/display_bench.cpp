// What showing a frame costs the master's window (issue 18), per frame, at a
// given size (default 1920x1080): median wall and process-CPU milliseconds of
//   accumulate  add the frame to the sum and resolve the mean (both versions)
//   to_srgb8 + drawpixels   before: sRGB on the CPU, 8-bit pixels drawn
//   upload + shader         after: floats uploaded, exposure and the view transform (its table) in a
//                           fragment shader, for each view; table: building a view's table (CPU)
//   build       the ImGui panel's lists (CPU): settings, cluster table of 8 workers, graph
//   panel, +overlay   build and draw, without and with the tile overlay (tint)
//   handover    the session thread's share: a completed frame's record (with its
//               tile sources) and the worker list moved into the display's queue
// Each GL step ends with glFinish, so the GPU's (or llvmpipe's) work is counted.
// Run under xvfb-run for a display: scripts/bench-display.sh.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <deque>
#include <mutex>
#include <string>
#include <vector>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <GL/gl.h>
#include <imgui.h>

#include "display/gl_image.h"
#include "display/image_view.h"
#include "display/window_panel.h"
#include "render/accumulator.h"

namespace {

using Clock = std::chrono::steady_clock;

double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

struct Figures {
  std::vector<double> wall_ms, cpu_ms;
  void print(const char* name) {
    std::sort(wall_ms.begin(), wall_ms.end());
    std::sort(cpu_ms.begin(), cpu_ms.end());
    std::printf("  %-10s median %8.3f ms wall  %8.3f ms CPU (process)  [min %.3f, max %.3f wall; %zu frames]\n", name,
                wall_ms[wall_ms.size() / 2], cpu_ms[cpu_ms.size() / 2], wall_ms.front(), wall_ms.back(), wall_ms.size());
  }
};

template <class F>
void time_frames(Figures& figures, int frames, F&& step) {
  for (int i = 0; i < frames; ++i) {
    const auto start = Clock::now();
    const double cpu = cpu_seconds();
    step(i);
    figures.wall_ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
    figures.cpu_ms.push_back(1e3 * (cpu_seconds() - cpu));
  }
}

igi::Image test_frame(int width, int height, int i) {
  igi::Image image(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      image.at(x, y) = glm::vec3(float(x) / width, float(y) / height, float((x + y + i) % 97) / 97.0f);
  return image;
}

}  // namespace

int main(int argc, char** argv) {
  int width = 1920, height = 1080, frames = 20, workers = 8;
  if (argc > 2) width = std::atoi(argv[1]), height = std::atoi(argv[2]);
  if (argc > 3) frames = std::max(3, std::atoi(argv[3]));
  if (!glfwInit()) return std::fprintf(stderr, "display-bench: no display (run under xvfb-run)\n"), 1;
  glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);
  GLFWwindow* window = glfwCreateWindow(width, height, "display-bench", nullptr, nullptr);
  if (!window) return std::fprintf(stderr, "display-bench: cannot open a %dx%d window\n", width, height), 1;
  glfwMakeContextCurrent(window);
  glfwSwapInterval(0);
  std::printf("display-bench: %dx%d, %d frames each; GL renderer: %s\n", width, height, frames,
              reinterpret_cast<const char*>(glGetString(GL_RENDERER)));
  const igi::Image pass = test_frame(width, height, 0);
  igi::Accumulator accumulator(width, height);

  Figures accumulate, srgb_cpu, draw_pixels, upload, build, render_plain, render_overlay, handover, table;
  Figures shaders[igi::kViewTransforms.size()];
  igi::Image resolved;
  time_frames(accumulate, frames, [&](int) {
    accumulator.add(pass, 1.0);
    resolved = accumulator.resolve();
  });
  std::vector<unsigned char> bytes;
  time_frames(srgb_cpu, frames, [&](int) { bytes = igi::to_srgb8(resolved); });
  time_frames(draw_pixels, frames, [&](int) {
    igi::draw_srgb8(bytes, width, height);
    glFinish();
  });
  {
    igi::ImageView view;
    time_frames(upload, frames, [&](int) {
      view.upload(resolved);
      glFinish();
    });
    const igi::Viewport whole{0.0f, 0.0f, float(width), float(height), 1.0f};
    for (size_t v = 0; v < igi::kViewTransforms.size(); ++v) {
      const igi::ToneMapping tone{1.0f, igi::kViewTransforms[v]};
      time_frames(table, 3, [&](int) { (void)igi::view_table(tone.view); });
      view.draw(width, height, whole, tone);  // builds and uploads the view's table
      time_frames(shaders[v], frames, [&](int) {
        view.draw(width, height, whole, tone);
        glFinish();
      });
    }
  }

  igi::WindowPanel panel(window, igi::RenderSettings{}, igi::ToneMapping{}, igi::PanelOptions{});  // shown, no overlay
  igi::FrameRecord record;
  record.seconds = 0.05;
  std::vector<igi::PeerView> peers;
  for (int w = 0; w < workers; ++w) peers.push_back({"worker-" + std::to_string(w), uint32_t(w), 8, 0.1, 2.0});
  for (int y = 0, n = 0; y < height; y += 32)
    for (int x = 0; x < width; x += 32, ++n)
      record.tile_sources.push_back({{x, y, std::min(32, width - x), std::min(32, height - y), 1}, uint32_t(n % workers)});
  record.tiles = record.tile_sources.size();
  for (const igi::PeerView& p : peers) record.workers[p.name] = {record.tiles / workers, 0.3, 1000, 100};
  panel.frame_shown(record, peers, 20.0, "full");
  for (int i = 0; i < 2; ++i) panel.draw(i);  // ImGui lays a new window out in its first frames
  time_frames(build, frames, [&](int i) { panel.build(i); });
  time_frames(render_plain, frames, [&](int i) {
    panel.build(i);  // not timed apart: build is measured above
    panel.render();
    glFinish();
  });
  panel.set_overlay(igi::OverlayMode::Tint);
  time_frames(render_overlay, frames, [&](int i) {
    panel.build(i);
    panel.render();
    glFinish();
  });

  std::mutex mutex;
  std::deque<std::pair<igi::FrameRecord, std::vector<igi::PeerView>>> queue;
  std::vector<igi::FrameRecord> records(size_t(frames) * 10, record);  // as the session completes them
  time_frames(handover, frames * 10, [&](int i) {
    std::vector<igi::PeerView> views = peers;  // MasterSession::peer_views()
    std::lock_guard lock(mutex);
    queue.emplace_back(std::move(records[size_t(i)]), std::move(views));
  });

  std::printf("display thread, per frame shown:\n");
  accumulate.print("accumulate");
  srgb_cpu.print("to_srgb8");
  draw_pixels.print("drawpixels");
  upload.print("upload");
  for (size_t v = 0; v < igi::kViewTransforms.size(); ++v)
    shaders[v].print((std::string("shader ") + igi::view_name(igi::kViewTransforms[v])).c_str());
  std::printf("  before = accumulate + to_srgb8 + drawpixels; after = accumulate + upload + shader\n");
  std::printf("on a change of view (CPU):\n");
  table.print("table");
  std::printf("panel (every redraw):\n");
  build.print("build");
  render_plain.print("panel");
  render_overlay.print("+overlay");
  std::printf("  panel and +overlay: build and GL drawing together\n");
  std::printf("session thread, per frame completed:\n");
  handover.print("handover");
  std::printf("tiles in the overlay: %zu; workers in the table: %d\n", record.tile_sources.size(), workers);
  glfwDestroyWindow(window);
  glfwTerminate();
  return 0;
}
