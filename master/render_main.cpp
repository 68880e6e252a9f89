// igi-render: renders one image of a scene with one method, in this process.
#include <chrono>
#include <cstdio>
#include <iostream>
#include <optional>
#include <optional>

#include "camera_bookmark.h"
#include "cli/option_checks.h"
#include "display/image_window.h"
#include "render_options.h"
#include "render/offline_render.h"
#include "render/scene_state.h"
#include "scene/animation.h"
#include "scene/gltf_writer.h"
#include "scene/load_scene.h"

namespace {

int run(igi::RenderOptions o) {
  std::optional<igi::Camera> camera;  // a bad camera file stops us before the scene loads
  if (!o.camera_file.empty()) camera = igi::read_camera_file(o.camera_file);
  std::vector<std::string> warnings;
  igi::Scene scene = igi::load_scene(o.scene, &warnings, igi::sky_choice(o));
  for (const std::string& w : warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
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
  if (!o.quiet)
    options.progress = [start](float f) {
      double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      if (t > 1.0) std::fprintf(stderr, "\r%5.1f%%  %.1f s", 100.0 * f, t);
    };
  igi::OfflineResult r = igi::render_offline(state.context(), o.settings, frame, o.samples, options);
  if (!o.quiet) std::fprintf(stderr, "\r                      \r");
  igi::write_image(r.image, o.output, o.exposure);
  std::printf("%s: %s %dx%d, %d %s, %.3f s, %.1f Mrays (%.1f Mrays/s)\n", o.output.c_str(),
              igi::method_name(o.settings.method), o.width, o.height, o.samples,
              o.settings.method == igi::MethodKind::PathTracer ? "spp" : "passes", r.seconds,
              r.rays.total() * 1e-6, r.rays.total() * 1e-6 / r.seconds);
  if (o.show) {
    igi::WindowOptions window;
    window.title = "igi-render: " + o.scene + " (" + igi::method_name(o.settings.method) + ")";
    window.exposure = o.exposure;
    window.screenshot = o.screenshot;
    igi::show_image(r.image, window);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return igi::cli::run_program("igi-render", 1, 1, [&] {
    igi::RenderOptions o = igi::parse_render_options({argv + 1, argv + argc});
    if (o.help) { std::cout << igi::render_usage(argv[0]); return 0; }
    return run(o);
  });
}
