// igi-render: renders one image of a scene with one method, in this process.
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>

#include <unistd.h>

#include "view/camera_bookmark.h"
#include "cli/option_checks.h"
#include "display/image_window.h"
#include "image/exposure_check.h"
#include "options/render_options.h"
#include "render/offline_render.h"
#include "render/scene_state.h"
#include "scene/animation.h"
#include "scene/gltf_writer.h"
#include "scene/load_scene.h"

namespace {

std::atomic<bool> g_interrupted{false};  // Ctrl-C: the passes done so far are written, as partial
constexpr int kInterruptedStatus = 130;  // 128 + SIGINT, as a shell reports it

// "40 s", "3 min", "2.5 h"
std::string duration_text(double seconds) {
  char text[32];
  if (seconds < 90.0) std::snprintf(text, sizeof text, "%.0f s", seconds);
  else if (seconds < 5400.0) std::snprintf(text, sizeof text, "%.0f min", seconds / 60.0);
  else std::snprintf(text, sizeof text, "%.1f h", seconds / 3600.0);
  return text;
}

// frames.png -> frames.partial.png
std::string partial_path(const std::string& output) {
  const std::filesystem::path p(output);
  return (p.parent_path() / (p.stem().string() + ".partial" + p.extension().string())).string();
}

int run(igi::RenderOptions o) {
  std::optional<igi::Camera> camera;  // a bad camera file stops us before the scene loads
  if (!o.camera_file.empty()) camera = igi::read_camera_file(o.camera_file);
  igi::SceneMessages messages;
  igi::Scene scene = igi::load_scene(o.scene, igi::scene_options(o), &messages);
  for (const std::string& w : messages.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  if (!o.quiet)
    for (const std::string& n : messages.notices) std::fprintf(stderr, "igi-render: %s\n", n.c_str());
  if (auto note = igi::choose_caustics(o, scene); note && !o.quiet) std::fprintf(stderr, "igi-render: %s\n", note->c_str());
  if (camera) igi::place_camera(scene, *camera);
  if (!o.export_gltf.empty()) {
    igi::write_gltf(scene, o.export_gltf);
    std::printf("wrote %s\n", o.export_gltf.c_str());
    if (scene.environment_map)  // glTF's extras hold a constant sky only
      std::fprintf(stderr, "igi-render: the environment map is not in %s (its extras hold only the sky's scale); "
                           "render it with --environment FILE again\n", o.export_gltf.c_str());
    return 0;
  }
  const bool framing_camera = !scene.camera;
  igi::FrameSetup frame;
  frame.width = o.width;
  frame.height = o.height;
  frame.seed = o.seed;
  if (scene.animation && scene.animation->animated()) frame.pose.time = o.time;
  frame.camera = igi::scene_camera(scene, frame.pose.time);
  frame.pose.light_offset = o.light_offset;
  igi::SceneState state(std::move(scene));  // as a worker holds it: the same BVH, the same pixels
  state.set_pose(frame.pose);

  igi::FrameOptions options;
  options.threads = o.threads;
  options.tile_size = o.tile_size;
  auto start = std::chrono::steady_clock::now();
  const bool terminal = isatty(STDERR_FILENO);
  if (!o.quiet)
    options.progress = [start, terminal, shown = 0.0](float f) mutable {
      double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      // A terminal gets a line rewritten four times a second; a log a line every 10 s.
      if (t < 1.0 || t - shown < (terminal ? 0.25 : 10.0)) return;
      shown = t;
      const std::string left = f > 0.0f ? ", about " + duration_text(t / f * (1.0 - f)) + " left" : "";
      if (terminal)
        std::fprintf(stderr, "\r%5.1f%%  %.1f s%s   ", 100.0 * f, t, left.c_str());
      else
        std::fprintf(stderr, "igi-render: %.1f%% after %.1f s%s\n", 100.0 * f, t, left.c_str());
    };
  igi::OfflineResult r = igi::render_offline(state.context(), o.settings, frame, o.samples, options, &g_interrupted);
  if (!o.quiet && terminal) std::fprintf(stderr, "\r%60s\r", "");
  const bool partial = r.passes < r.planned;
  if (partial && r.passes == 0) {
    std::fprintf(stderr, "igi-render: interrupted before the first pass finished: nothing written\n");
    return kInterruptedStatus;
  }
  if (partial) o.output = partial_path(o.output);
  const igi::ToneMapping tone{igi::exposure_for(r.image, o.exposure), o.view};
  igi::write_image(r.image, o.output, tone);
  if (o.exposure.metered && !o.quiet && !igi::is_float_format(o.output))
    std::fprintf(stderr, "igi-render: exposure metered: %+.2f EV (x %.4g)\n", std::log2(tone.exposure), tone.exposure);
  if (auto advice = igi::exposure_advice(r.image, {tone.exposure, o.exposure.metered, o.view,
                                                   !igi::is_float_format(o.output), messages.file_lamps > 0,
                                                   o.light_units == igi::LightUnits::Photometric, framing_camera}))
    std::fprintf(stderr, "igi-render: %s\n", advice->c_str());
  if (partial) {
    std::fprintf(stderr, "igi-render: interrupted after %d of %d passes: wrote them to %s\n", r.passes, r.planned,
                 o.output.c_str());
    return kInterruptedStatus;
  }
  std::printf("%s: %s %dx%d, %d %s, %.3f s, %.1f Mrays (%.1f Mrays/s)\n", o.output.c_str(),
              igi::method_name(o.settings.method), o.width, o.height, o.samples,
              o.settings.method == igi::MethodKind::PathTracer ? "spp" : "passes", r.seconds,
              r.rays.total() * 1e-6, r.rays.total() * 1e-6 / r.seconds);
  if (o.show) {
    igi::WindowOptions window;
    window.title = "igi-render: " + o.scene + " (" + igi::method_name(o.settings.method) + ")";
    window.tone = tone;
    window.screenshot = o.screenshot;
    igi::show_image(r.image, window);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  // The first Ctrl-C ends the render after the pass under way; a second ends the process at once.
  auto interrupt = [](int) {
    if (g_interrupted.exchange(true)) std::_Exit(kInterruptedStatus);
    const char note[] = "\nigi-render: stopping after this pass (Ctrl-C again to quit without writing)\n";
    (void)!write(STDERR_FILENO, note, sizeof note - 1);
  };
  std::signal(SIGINT, interrupt);
  std::signal(SIGTERM, interrupt);
  return igi::cli::run_program("igi-render", 1, 1, [&] {
    igi::RenderOptions o = igi::parse_render_options({argv + 1, argv + argc});
    if (o.help) { std::cout << igi::render_usage(argv[0]); return 0; }
    return run(o);
  });
}
