// igi-importance: light importance and bidirectional IR against plain ir/igi,
// all variants measured in one run on one machine. Per variant (igi-render
// options), over several seeds: wall and CPU time, relMSE, LDR-FLIP and mean
// ratio against a reference, VPLs per set, the rays begin_frame() traced,
// and the share of VPLs that see what the camera sees.
//
//   igi-importance --scene S --size WxH --ref REF.exr [--seeds N] [--passes P] [--no-flip]
//                  --variant "OPTIONS" [--variant "OPTIONS" ...]
//   igi-importance --scene S --size WxH --flicker STEP [--frames F] --variant ...
//
// --flicker: no reference; F frames (6) with the camera sliding STEP metres a
// frame to its right, the same seed every frame, and per variant the
// flicker: the mean absolute luminance change between consecutive frames
// over their mean luminance (test_stability.cpp's measure, over the whole
// image), averaged over --seeds runs of seeds 1, 1001, ...
//
// Seen: of the first pass's VPLs (all sets), the share in rooms where the
// camera sees a point (scene/suite_scenes.h suite_room(); one room in scenes
// without rooms), as igi-accuracy's vpls_seen.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <sstream>

#include "bench/bench_scene.h"
#include "image/flip.h"
#include "image/metrics.h"
#include "methods/vpl_method.h"
#include "render/accumulator.h"
#include "render/frame_renderer.h"
#include "options/render_options.h"
#include "sampling/sobol.h"
#include "sampling/warp.h"
#include "scene/camera_rays.h"
#include "scene/load_scene.h"
#include "scene/suite_scenes.h"

namespace igi {
namespace {

struct Options {
  std::string scene = "rooms";
  int width = 128, height = 96;
  std::string reference;
  int seeds = 3, passes = 1;
  bool flip = true;
  float flicker_step = 0.0f;  // > 0: measure flicker instead
  int frames = 6;
  std::vector<std::string> variants;
};

void declare(CLI::App& app, Options& o) {
  app.add_option("--scene", o.scene, "[rooms]");
  cli::add_size_option(app, "--size", o.width, o.height, 16384, "[128x96]");
  app.add_option("--ref", o.reference, "reference image")->type_name("REF.exr");
  app.add_option("--seeds", o.seeds, "runs, seeds 1, 1001, ... [3]")->check(cli::integer(1, 100000));
  app.add_option("--passes", o.passes, "progressive passes [1]")->check(cli::integer(1, 100000));
  app.add_flag_callback("--no-flip", [&o] { o.flip = false; }, "no FLIP");
  app.add_option("--flicker", o.flicker_step, "measure flicker: the camera slides STEP metres a frame")
      ->check(cli::non_negative_number())->type_name("STEP");
  app.add_option("--frames", o.frames, "flicker frames [6]")->check(cli::integer(2, 100000));
  app.add_option("--variant", o.variants, "igi-render options of a variant (repeatable)")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)->type_name("\"OPTIONS\"");
}

Options parse(int argc, char** argv) {
  Options o = bench::parse_options<Options>("igi-importance: light importance and bidirectional IR against plain "
                                            "ir/igi (see the header of tests/bench/importance_bench.cpp)",
                                            "igi-importance", argc, argv, declare);
  if ((o.reference.empty() && o.flicker_step <= 0.0f) || o.variants.empty())
    throw std::invalid_argument("need --ref (or --flicker) and at least one --variant");
  return o;
}

RenderSettings variant_settings(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> args;
  for (std::string a; in >> a;) args.push_back(a);
  return parse_render_options(args).settings;
}

double cpu_seconds() {
  timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

// Share of VPLs in rooms where the camera sees a point (through a 32 x 32
// grid of pixel centres): scene/suite_scenes.h suite_room().
double visible_share(const std::string& scene_name, const SceneContext& context, const FrameSetup& frame,
                     const VplSets& sets) {
  const CameraBasis camera(frame.camera, frame.width, frame.height);
  std::vector<int> rooms;
  for (int j = 0; j < 32; ++j)
    for (int i = 0; i < 32; ++i) {
      Ray ray = camera.ray((float(i) + 0.5f) * float(frame.width) / 32.0f, (float(j) + 0.5f) * float(frame.height) / 32.0f);
      ray.mask = kCameraRayMask;
      Hit hit;
      if (context.accel.intersect(ray, hit)) rooms.push_back(suite_room(scene_name, ray.origin + hit.t * ray.direction));
    }
  size_t seen = 0;
  for (const Vpl& v : sets.vpls) seen += std::find(rooms.begin(), rooms.end(), suite_room(scene_name, v.position)) != rooms.end();
  return sets.vpls.empty() ? 0.0 : double(seen) / double(sets.vpls.size());
}

struct Run {
  double wall, cpu, relmse, flip, mean_ratio, vpls_per_set, setup_rays_per_pass, visible;
};

Run render(const SceneContext& context, const RenderSettings& settings, const Options& o, uint32_t seed,
           const Image& reference) {
  auto method = make_method(context, settings);
  auto* vpl = dynamic_cast<VplMethod*>(method.get());
  FrameSetup base;
  base.camera = context.scene.camera_or_auto();
  base.width = o.width;
  base.height = o.height;
  base.seed = seed;
  Accumulator accumulator(o.width, o.height);
  RayCounts rays;
  Run run{};
  const double cpu0 = cpu_seconds();
  const auto wall0 = std::chrono::steady_clock::now();
  for (int pass = 0; pass < o.passes; ++pass) {
    FrameSetup frame = base;
    if (o.passes > 1) {  // as render_offline
      frame.seed = base.seed + uint32_t(pass);
      const glm::vec2 jitter = sample_2d(uint32_t(pass), 0, base.seed);
      frame.jitter_x = jitter.x;
      frame.jitter_y = jitter.y;
    }
    method->begin_frame(frame);
    if (vpl) {
      run.setup_rays_per_pass += double(vpl->setup_rays().total()) / o.passes;
      run.vpls_per_set += double(vpl->vpls().vpls.size()) / vpl->vpls().set_count() / o.passes;
    }
    accumulator.add(render_frame(*method, frame, tile_border(settings), FrameOptions{}, rays), 1.0);
  }
  run.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  run.cpu = cpu_seconds() - cpu0;
  const Image image = accumulator.resolve();
  run.relmse = rel_mse(image, reference);
  run.flip = o.flip ? mean_flip(image, reference) : 0.0;
  run.mean_ratio = luminance(image.mean()) / luminance(reference.mean());
  if (vpl) {
    method->begin_frame(base);
    run.visible = visible_share(o.scene, context, base, vpl->vpls());
  }
  return run;
}

// Mean |L(f) - L(f - 1)| over mean L along the sliding camera, with the CPU time per frame.
void flicker(const SceneContext& context, const RenderSettings& settings, const Options& o, uint32_t seed,
             double& value, double& cpu_per_frame) {
  auto method = make_method(context, settings);
  Image previous;
  double change = 0.0, level = 0.0;
  const double cpu0 = cpu_seconds();
  for (int f = 0; f < o.frames; ++f) {
    FrameSetup frame;
    frame.camera = context.scene.camera_or_auto();
    const glm::vec3 right = glm::normalize(glm::cross(frame.camera.forward, frame.camera.up));
    frame.camera.position += right * (o.flicker_step * float(f));
    frame.width = o.width;
    frame.height = o.height;
    frame.seed = seed;
    method->begin_frame(frame);
    RayCounts rays;
    const Image image = render_frame(*method, frame, tile_border(settings), FrameOptions{}, rays);
    if (f > 0)
      for (size_t i = 0; i < image.pixels.size(); ++i) {
        change += std::abs(luminance(image.pixels[i]) - luminance(previous.pixels[i]));
        level += luminance(image.pixels[i]);
      }
    previous = image;
  }
  cpu_per_frame = (cpu_seconds() - cpu0) / o.frames;
  value = change / level;
}

int run_flicker(const Options& o, const SceneContext& context) {
  std::printf("%-48s %9s %9s\n", "variant", "flicker", "cpu_s/fr");
  for (const std::string& text : o.variants) {
    double value = 0.0, cpu = 0.0;
    for (int s = 0; s < o.seeds; ++s) {
      double v = 0.0, c = 0.0;
      flicker(context, variant_settings(text), o, 1u + 1000u * uint32_t(s), v, c);
      value += v / o.seeds;
      cpu += c / o.seeds;
    }
    std::printf("%-48s %9.5f %9.3f\n", text.c_str(), value, cpu);
    std::fflush(stdout);
  }
  return 0;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

int run(const Options& o) {
  const Scene scene = load_scene(o.scene);
  const Accel accel(scene);
  const LightSet lights(scene);
  const SceneContext context{scene, accel, lights};
  if (o.flicker_step > 0.0f) return run_flicker(o, context);
  const Image reference = read_image(o.reference);
  if (reference.width != o.width || reference.height != o.height) throw std::invalid_argument("--ref: size differs from --size");
  std::printf("%-48s %7s %7s %9s %9s %7s %6s %7s %9s %6s\n", "variant", "wall_s", "cpu_s", "relMSE", "mean_rel", "FLIP",
              "mean", "vpls", "setup_ray", "seen");
  for (const std::string& text : o.variants) {
    const RenderSettings settings = variant_settings(text);
    std::vector<double> wall, cpu, relmse, flip, mean, vpls, setup, seen;
    for (int s = 0; s < o.seeds; ++s) {
      const Run r = render(context, settings, o, 1u + 1000u * uint32_t(s), reference);
      wall.push_back(r.wall); cpu.push_back(r.cpu); relmse.push_back(r.relmse); flip.push_back(r.flip);
      mean.push_back(r.mean_ratio); vpls.push_back(r.vpls_per_set); setup.push_back(r.setup_rays_per_pass);
      seen.push_back(r.visible);
    }
    double mean_relmse = 0.0;
    for (double e : relmse) mean_relmse += e / double(relmse.size());
    std::printf("%-48s %7.3f %7.3f %9.5f %9.5f %7.4f %6.3f %7.1f %9.0f %6.3f\n", text.c_str(), median(wall), median(cpu),
                median(relmse), mean_relmse, median(flip), median(mean), median(vpls), median(setup), median(seen));
    std::fflush(stdout);
  }
  return 0;
}

}  // namespace
}  // namespace igi

int main(int argc, char** argv) {
  return igi::bench::run_main("igi-importance", [&] { return igi::run(igi::parse(argc, argv)); });
}
