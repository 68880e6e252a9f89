// igi-dynamic-bench: what moving parts cost. Prints figures; asserts nothing.
//
//   igi-dynamic-bench [frames] [width] [height]   (default 9 frames, 256 x 192)
//
// 1. Throughput (Mrays/s) of igi on an animated scene against the same scene
//    static (both as a worker holds them: two levels, the area lights a part
//    the window can move), and the static scene traced single-level as
//    before scenes could move; frames alternate so load from other
//    processes falls on all alike:
//    cornell-blob with its blob moving, and a scene of 10^6 triangles with
//    one small moving ball. Every animated frame poses the scene first
//    (SceneState::set_pose: the moving parts' BVHs, the top level, the
//    lights); the pose's time is counted in the frame.
// 2. The update alone: set_pose's median time per frame on the 10^6-triangle
//    scene against a 5 x 10^4-triangle one with the same ball: the cost must
//    not grow with the static geometry.
// 3. Flicker: mean absolute luminance change between consecutive frames of
//    the animation over the pixels where nothing moved (the same static
//    triangle seen in both), with the VPL seed kept (as the renderer does)
//    against a new seed every frame.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <vector>

#include "bench/bench_clock.h"
#include "core/gbuffer.h"
#include "render/frame_renderer.h"
#include "render/scene_state.h"
#include "scene/builtin_scenes.h"
#include "scene/suite_scenes.h"

namespace igi {
namespace {

using bench::Clock;
using bench::median;

RenderSettings igi_settings() {
  RenderSettings s;
  s.method = MethodKind::Igi;
  return s;
}

FrameSetup frame_at(const Scene& scene, int width, int height, double time, uint32_t seed) {
  FrameSetup f;
  f.camera = scene.camera_or_auto();
  f.width = width;
  f.height = height;
  f.seed = seed;
  f.pose.time = time;
  return f;
}

struct FrameFigures {
  double seconds = 0.0, update = 0.0;
  uint64_t rays = 0;
};

// One frame as a worker renders it: pose, make the method, begin, render.
FrameFigures render_one(SceneState& state, const FrameSetup& frame, Image* out = nullptr) {
  FrameFigures f;
  const Clock start = Clock::now();
  state.set_pose(frame.pose);
  f.update = (Clock::now() - start).wall;
  const RenderSettings settings = igi_settings();
  auto method = make_method(state.context(), settings);
  method->begin_frame(frame);
  RayCounts rays;
  FrameOptions options;
  Image image = render_frame(*method, frame, tile_border(settings), options, rays);
  f.seconds = (Clock::now() - start).wall;
  f.rays = rays.total();
  if (out) *out = std::move(image);
  return f;
}

// The static scene traced single-level: no light group, no instance.
FrameFigures render_single_level(const Scene& scene, const Accel& accel, const LightSet& lights,
                                 const FrameSetup& frame) {
  FrameFigures f;
  const Clock start = Clock::now();
  const RenderSettings settings = igi_settings();
  auto method = make_method({scene, accel, lights}, settings);
  method->begin_frame(frame);
  RayCounts rays;
  render_frame(*method, frame, tile_border(settings), FrameOptions{}, rays);
  f.seconds = (Clock::now() - start).wall;
  f.rays = rays.total();
  return f;
}

void throughput(const char* label, const Scene& static_scene, Scene moving_scene, int frames, int width,
                int height) {
  const Accel plain_accel(static_scene);
  const LightSet plain_lights(static_scene);
  SceneState still(static_scene), moving(std::move(moving_scene));
  std::vector<double> plain_rate, still_rate, moving_rate, updates;
  for (int i = -1; i < frames; ++i) {  // frame -1 warms all up
    const double time = (i + 1) / 30.0;
    const FrameFigures p = render_single_level(static_scene, plain_accel, plain_lights,
                                               frame_at(static_scene, width, height, 0.0, 1));
    const FrameFigures a = render_one(still, frame_at(still.scene(), width, height, 0.0, 1));
    const FrameFigures b = render_one(moving, frame_at(moving.scene(), width, height, time, 1));
    if (i < 0) continue;
    plain_rate.push_back(p.rays / p.seconds * 1e-6);
    still_rate.push_back(a.rays / a.seconds * 1e-6);
    moving_rate.push_back(b.rays / b.seconds * 1e-6);
    updates.push_back(b.update);
  }
  const double p = median(plain_rate), s = median(still_rate), m = median(moving_rate);
  std::printf("%-22s | %8.2f | %8.2f | %8.2f | %6.1f %% | %6.1f %% | %8.3f\n", label, p, s, m, 100.0 * s / p,
              100.0 * m / s, 1e3 * median(updates));
}

void update_cost(int frames) {
  std::printf("\nupdate (set_pose) of one moving ball of %s triangles, median of %d frames, 2 threads or all:\n",
              "2 256", frames);
  std::printf("%-22s | %10s | %9s\n", "scene", "triangles", "update ms");
  for (int triangles : {50'000, 1'050'000}) {
    SceneState state(make_large_moving(triangles));
    std::vector<double> times;
    for (int i = 0; i <= frames; ++i) {
      const Clock start = Clock::now();
      state.set_pose(ScenePose{(i + 1) / 30.0, glm::vec3(0.0f)});
      if (i > 0) times.push_back((Clock::now() - start).wall);
    }
    std::printf("%-22s | %10zu | %9.3f\n", "large-moving", state.scene().triangles.size(), 1e3 * median(times));
  }
}

// Pixels whose primary hit is the same static triangle in both frames.
std::vector<bool> unmoved_pixels(SceneState& state, const FrameSetup& a, const FrameSetup& b) {
  std::vector<bool> moving(state.scene().triangles.size(), false);
  for (const DynamicPart& part : state.scene().animation->parts)
    if (part.node >= 0)
      for (uint32_t t : part.triangles) moving[t] = true;
  auto hits = [&](const FrameSetup& f) {
    state.set_pose(f.pose);
    GBuffer g;
    RayCounts rays;
    build_gbuffer(state.accel(), f, Region{0, 0, f.width, f.height}, 1, 1, 16, g, rays);
    return g.layers;
  };
  const std::vector<GSample> ha = hits(a), hb = hits(b);
  std::vector<bool> out(ha.size());
  for (size_t i = 0; i < ha.size(); ++i)
    out[i] = ha[i].has_surface && hb[i].has_surface && ha[i].surface.triangle == hb[i].surface.triangle &&
             !moving[ha[i].surface.triangle];
  return out;
}

void flicker(int width, int height) {
  SceneState state(make_large_moving(50'000));
  double sum_kept = 0.0, sum_new = 0.0, sum_level = 0.0;
  size_t count = 0;
  const int pairs = 4;
  for (int i = 0; i < pairs; ++i) {
    const double t0 = 0.3 + i / 30.0, t1 = t0 + 1.0 / 30.0;
    const FrameSetup a = frame_at(state.scene(), width, height, t0, 1);
    FrameSetup b = frame_at(state.scene(), width, height, t1, 1);
    const std::vector<bool> mask = unmoved_pixels(state, a, b);
    Image ia, ib, ic;
    render_one(state, a, &ia);
    render_one(state, b, &ib);
    b.seed = 2 + uint32_t(i);
    render_one(state, b, &ic);
    for (size_t p = 0; p < mask.size(); ++p) {
      if (!mask[p]) continue;
      auto lum = [](glm::vec3 c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; };
      sum_kept += std::abs(lum(ib.pixels[p]) - lum(ia.pixels[p]));
      sum_new += std::abs(lum(ic.pixels[p]) - lum(ia.pixels[p]));
      sum_level += lum(ia.pixels[p]);
      ++count;
    }
  }
  std::printf("\nflicker on large-moving (5 x 10^4 triangles, the ball moving), %dx%d, %d frame pairs 1/30 s apart,\n"
              "%zu unmoved pixels: mean |change in luminance| / mean luminance\n",
              width, height, pairs, count);
  std::printf("  same VPL seed every frame (the renderer): %.5f\n", sum_kept / sum_level);
  std::printf("  new VPL seed every frame:                 %.5f\n", sum_new / sum_level);
}

}  // namespace
}  // namespace igi

int main(int argc, char** argv) {
  using namespace igi;
  const int frames = argc > 1 ? std::max(1, std::atoi(argv[1])) : 9;
  const int width = argc > 2 ? std::max(16, std::atoi(argv[2])) : 256;
  const int height = argc > 3 ? std::max(16, std::atoi(argv[3])) : 192;
  std::printf("igi %dx%d, %d threads, median of %d frames; Mrays/s include posing the scene\n", width, height,
              default_thread_count(), frames);
  std::printf("%-22s | %8s | %8s | %8s | %8s | %8s | %8s\n", "scene", "1-level", "static", "moving", "st/1-lv",
              "mov/st", "update ms");
  throughput("cornell-blob (320k)", make_cornell_blob(320'000), make_cornell_blob_moving(320'000), frames, width,
             height);
  throughput("large (10^6) + ball", make_large_scene(), make_large_moving(), frames, width, height);
  update_cost(frames);
  flicker(width / 2, height / 2);
  return 0;
}
