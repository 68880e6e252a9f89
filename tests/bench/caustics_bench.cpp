// igi-caustics-bench: what the caustic photon map costs and what it buys.
// Asserts nothing; scripts/bench-caustics.sh runs it and draws the charts.
//
//   igi-caustics-bench [--scene glass] [--photons 1000,10000,...] [--frames F]
//                      [--threads T] [--fps-size WxH] [--size WxH] [--ref FILE.exr]
//                      [--out DIR] [--skip-pass] [--skip-fps] [--skip-reach]
//
// Three parts, every figure from this one run (ratios within it):
//  1. pass: the photon pass alone (trace the frame's photon paths on T
//     threads, grid them) per photon count, median of F frames (seeds 1..F),
//     wall and process CPU time, photons stored, rays; and the density
//     estimate's cost per pixel (one thread, every pixel centre of a
//     --fps-size frame that sees a diffuse surface) -> DIR/pass.csv.
//  2. fps: whole frames of igi at --fps-size (640x480) on T threads, 40x40
//     tiles and --fps-vpl-paths (6: scripts/bench-igi.sh's setting), on the
//     Cornell box (the baseline), then on the scene without caustics and with
//     them at each photon count (median of F frames, photon pass included)
//     -> DIR/fps.csv.
//  3. reach: time for pt and for igi with caustics to reach relMSE 0.03 and
//     FLIP 0.1 against the converged reference --ref at --size (its size):
//     pt doubles its samples per pixel, igi its progressive passes (each a
//     fresh frame: new VPLs, photons and sub-pixel position), each series
//     until both thresholds are met or its budget is spent -> DIR/reach.csv
//     (every point) and DIR/reach.md (the time to each threshold and the
//     ratio pt / igi).
//  4. branches (needs --ref): igi with caustics at --glass-branches 1, 2, 3,
//     4 and 8, one and four passes: time, and relMSE and FLIP over the whole
//     image and over the pixels whose camera ray meets glass first (where a
//     per-pixel choice of reflection or refraction shows as salt and pepper)
//     -> DIR/branches.csv.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "bench/bench_scene.h"
#include "bench/bench_clock.h"
#include "image/flip.h"
#include "image/metrics.h"
#include "methods/vpl_method.h"
#include "photons/caustic_settings.h"
#include "render/frame_renderer.h"
#include "render/offline_render.h"
#include "scene/camera_rays.h"
#include "scene/load_scene.h"

namespace igi {
namespace {

using bench::Clock;
using bench::median;

namespace fs = std::filesystem;

constexpr double kRelMseTarget = 0.03, kFlipTarget = 0.1;

struct Options {
  std::string scene = "glass";
  std::vector<int> photons = {1000, 3000, 10000, 30000, 100000, 300000, 1000000};
  int frames = 5;
  int threads = 2;
  int fps_width = 640, fps_height = 480;
  std::string ref;
  std::string out = "results/caustics";
  bool pass = true, fps = true, reach = true, branches = true;
  int vpl_paths = 16;
  int fps_vpl_paths = 6;
  float clamp = 0.0f;
  std::vector<int> reach_photons = {10000, 30000, 100000};
};

void declare(CLI::App& app, Options& o) {
  using cli::integer;
  const int max_photons = photons::kMaxCausticPhotons;
  app.add_option("--scene", o.scene, "[glass]");
  app.add_option("--photons", o.photons, "photon paths a frame, comma-separated [1000,...,1000000]")
      ->delimiter(',')->check(integer(1, max_photons));
  app.add_option("--reach-photons", o.reach_photons, "reach: photon counts [10000,30000,100000]")->delimiter(',')
      ->check(integer(1, max_photons));
  app.add_option("--frames", o.frames, "frames, median [5]")->check(integer(1, 100000));
  app.add_option("--threads", o.threads, "[2]")->check(integer(0, cli::kMaxThreads));
  cli::add_size_option(app, "--fps-size", o.fps_width, o.fps_height, 16384, "fps: frame size [640x480]");
  app.add_option("--ref", o.ref, "converged reference (reach, branches)")->type_name("FILE.exr");
  app.add_option("--out", o.out, "folder [results/caustics]")->type_name("DIR");
  app.add_option("--vpl-paths", o.vpl_paths, "[16]")->check(integer(1, kMaxPathsPerSet));
  app.add_option("--fps-vpl-paths", o.fps_vpl_paths, "[6]")->check(integer(1, kMaxPathsPerSet));
  app.add_option("--clamp", o.clamp, "[0]")->check(cli::non_negative_number());
  app.add_flag_callback("--skip-pass", [&o] { o.pass = false; }, "leave out part 1");
  app.add_flag_callback("--skip-fps", [&o] { o.fps = false; }, "leave out part 2");
  app.add_flag_callback("--skip-reach", [&o] { o.reach = false; }, "leave out part 3");
  app.add_flag_callback("--skip-branches", [&o] { o.branches = false; }, "leave out part 4");
}

Options parse(int argc, char** argv) {
  Options o = bench::parse_options<Options>("igi-caustics-bench: what the caustic photon map costs and what it buys "
                                            "(see the header of tests/bench/caustics_bench.cpp)",
                                            "igi-caustics-bench", argc, argv, declare);
  if ((o.reach || o.branches) && o.ref.empty())
    throw std::invalid_argument("--ref: the converged reference is needed (or --skip-reach --skip-branches)");
  return o;
}

using Prepared = bench::PreparedScene;

RenderSettings igi_settings(const Options& o, int photons) {
  RenderSettings s;
  s.method = MethodKind::Igi;
  s.paths_per_set = o.vpl_paths;
  s.clamp = o.clamp;
  s.caustics = photons > 0;
  if (photons > 0) s.caustic_photons = photons;
  return s;
}

void bench_pass(const Prepared& p, const Options& o) {
  std::ofstream csv(o.out + "/pass.csv");
  csv << "scene,photon_paths,threads,ms,cpu_ms,photons_stored,rays,ns_per_path,estimate_ns_per_pixel\n";
  std::printf("photon pass (%s, %d threads, median of %d frames)\n%10s %9s %9s %10s %10s %9s %12s\n", o.scene.c_str(),
              o.threads, o.frames, "paths", "ms", "cpu ms", "photons", "rays", "ns/path", "estimate ns");
  GBuffer gbuffer;
  RayCounts rays;
  build_gbuffer(p.accel, p.frame(o.fps_width, o.fps_height, 1), Region{0, 0, o.fps_width, o.fps_height}, 1, 1, 16,
                gbuffer, rays);
  for (int n : o.photons) {
    CausticMap map(p.context(), igi_settings(o, n));
    std::vector<double> wall, cpu;
    for (int f = 0; f < o.frames; ++f) {
      const Clock start = Clock::now();
      map.build(uint32_t(f + 1), o.threads);
      const Clock d = Clock::now() - start;
      wall.push_back(d.wall);
      cpu.push_back(d.cpu);
    }
    const double ms = 1e3 * median(wall), cpu_ms = 1e3 * median(cpu);
    std::vector<double> estimate;
    glm::vec3 keep(0.0f);  // so the estimates are not optimised away
    for (int f = 0; f < 3; ++f) {
      size_t pixels = 0;
      const Clock start = Clock::now();
      for (const GSample& g : gbuffer.layers)
        if (g.valid()) { keep += map.radiance(g); ++pixels; }
      estimate.push_back(1e9 * (Clock::now() - start).cpu / double(std::max<size_t>(pixels, 1)));
    }
    char line[256];
    std::snprintf(line, sizeof line, "%s,%d,%d,%.3f,%.3f,%zu,%llu,%.1f,%.1f\n", o.scene.c_str(), n, o.threads, ms, cpu_ms,
                  map.photon_count(), (unsigned long long)map.rays().total(), 1e6 * ms / n, median(estimate));
    csv << line;
    std::printf("%10d %9.2f %9.2f %10zu %10llu %9.1f %12.1f%s\n", n, ms, cpu_ms, map.photon_count(),
                (unsigned long long)map.rays().total(), 1e6 * ms / n, median(estimate), keep.x < 0 ? " " : "");
  }
}

// Median whole-frame time of igi (photon pass included), wall and CPU.
Clock frame_time(const Prepared& p, const RenderSettings& s, const Options& o) {
  FrameOptions options;
  options.threads = o.threads;
  options.tile_size = 40;
  auto method = make_method(p.context(), s);
  std::vector<double> wall, cpu;
  for (int f = 0; f < o.frames; ++f) {
    const FrameSetup frame = p.frame(o.fps_width, o.fps_height, uint32_t(f + 1));
    RayCounts rays;
    const Clock start = Clock::now();
    method->begin_frame(frame);
    render_frame(*method, frame, tile_border(s), options, rays);
    const Clock d = Clock::now() - start;
    wall.push_back(d.wall);
    cpu.push_back(d.cpu);
  }
  return {median(wall), median(cpu)};
}

void bench_fps(const Prepared& p, const Options& o) {
  std::ofstream csv(o.out + "/fps.csv");
  csv << "scene,width,height,threads,vpl_paths,photon_paths,ms,cpu_ms,fps\n";
  std::printf("\nigi frames at %dx%d on %d threads, %d paths per set (median of %d; photon pass included)\n"
              "%-8s %10s %9s %9s %7s\n",
              o.fps_width, o.fps_height, o.threads, o.fps_vpl_paths, o.frames, "scene", "paths", "ms", "cpu ms", "fps");
  auto row = [&](const Prepared& scene, const std::string& name, int n) {
    RenderSettings s = igi_settings(o, n);
    s.paths_per_set = o.fps_vpl_paths;
    const Clock t = frame_time(scene, s, o);
    char line[256];
    std::snprintf(line, sizeof line, "%s,%d,%d,%d,%d,%d,%.2f,%.2f,%.2f\n", name.c_str(), o.fps_width, o.fps_height,
                  o.threads, o.fps_vpl_paths, n, 1e3 * t.wall, 1e3 * t.cpu, 1.0 / t.wall);
    csv << line;
    std::printf("%-8s %10d %9.1f %9.1f %7.2f\n", name.c_str(), n, 1e3 * t.wall, 1e3 * t.cpu, 1.0 / t.wall);
  };
  row(Prepared(load_scene("cornell")), "cornell", 0);
  row(p, o.scene, 0);
  for (int n : o.photons) row(p, o.scene, n);
}

struct Reached {
  double relmse_seconds = -1, flip_seconds = -1;
  std::string relmse_at, flip_at;
  double best_relmse = 1e30, best_flip = 1e30;
};

// One point of a series: render, time it (wall; CPU beside it), compare.
void reach_point(const Prepared& p, const Image& ref, const RenderSettings& s, int samples, const std::string& label,
                 std::ofstream& csv, Reached& r) {
  FrameOptions options;
  const Clock start = Clock::now();
  const OfflineResult result = render_offline(p.context(), s, p.frame(ref.width, ref.height, 1), samples, options);
  const Clock d = Clock::now() - start;
  const double e = rel_mse(result.image, ref), f = mean_flip(result.image, ref);
  char line[256];
  std::snprintf(line, sizeof line, "%s,%s,%d,%.4f,%.4f,%.6g,%.6g\n", method_name(s.method), label.c_str(), samples,
                d.wall, d.cpu, e, f);
  csv << line;
  csv.flush();
  std::printf("  %-4s %-22s %6d  %8.3f s (cpu %7.3f)  relMSE %.5f  FLIP %.4f\n", method_name(s.method), label.c_str(),
              samples, d.wall, d.cpu, e, f);
  r.best_relmse = std::min(r.best_relmse, e);
  r.best_flip = std::min(r.best_flip, f);
  const std::string at = label + ", " + std::to_string(samples) + (s.method == MethodKind::PathTracer ? " spp" : " passes");
  if (e <= kRelMseTarget && (r.relmse_seconds < 0 || d.wall < r.relmse_seconds)) { r.relmse_seconds = d.wall; r.relmse_at = at; }
  if (f <= kFlipTarget && (r.flip_seconds < 0 || d.wall < r.flip_seconds)) { r.flip_seconds = d.wall; r.flip_at = at; }
}

std::string shown(double seconds, double best, const std::string& at) {
  char text[160];
  if (seconds < 0) std::snprintf(text, sizeof text, "not reached (best %.4g)", best);
  else std::snprintf(text, sizeof text, "%.3f s (%s)", seconds, at.c_str());
  return text;
}

void bench_reach(const Prepared& p, const Options& o) {
  const Image ref = read_image(o.ref);
  std::ofstream csv(o.out + "/reach.csv");
  csv << "method,settings,samples,seconds,cpu_seconds,relmse,flip\n";
  std::printf("\ntime to relMSE %.2f and FLIP %.2f against %s (%dx%d, all threads)\n", kRelMseTarget, kFlipTarget,
              o.ref.c_str(), ref.width, ref.height);
  Reached pt;
  RenderSettings pts;
  pts.method = MethodKind::PathTracer;
  for (int spp = 4; spp <= 4096; spp *= 2) {
    reach_point(p, ref, pts, spp, "pt", csv, pt);
    if (pt.relmse_seconds >= 0 && pt.flip_seconds >= 0) break;
  }
  std::vector<std::pair<std::string, Reached>> igi;
  for (int n : o.reach_photons) {
    Reached r;
    const RenderSettings s = igi_settings(o, n);
    for (int passes = 1; passes <= 64; passes *= 2) {
      reach_point(p, ref, s, passes, "photons=" + std::to_string(n), csv, r);
      if (r.relmse_seconds >= 0 && r.flip_seconds >= 0) break;
    }
    igi.emplace_back("igi, " + std::to_string(n) + " photon paths", r);
  }
  Reached none;
  for (int passes = 1; passes <= 16; passes *= 4) reach_point(p, ref, igi_settings(o, 0), passes, "no caustics", csv, none);
  igi.emplace_back("igi without caustics", none);
  std::ofstream md(o.out + "/reach.md");
  md << "| method | relMSE <= 0.03 | FLIP <= 0.1 | pt / this (relMSE) | pt / this (FLIP) |\n|---|---|---|---|---|\n";
  auto ratio = [](double a, double b) {
    char t[32];
    if (a < 0 || b <= 0) return std::string("-");
    std::snprintf(t, sizeof t, "%.1fx", a / b);
    return std::string(t);
  };
  md << "| pt | " << shown(pt.relmse_seconds, pt.best_relmse, pt.relmse_at) << " | "
     << shown(pt.flip_seconds, pt.best_flip, pt.flip_at) << " | | |\n";
  for (const auto& [name, r] : igi)
    md << "| " << name << " | " << shown(r.relmse_seconds, r.best_relmse, r.relmse_at) << " | "
       << shown(r.flip_seconds, r.best_flip, r.flip_at) << " | " << ratio(pt.relmse_seconds, r.relmse_seconds) << " | "
       << ratio(pt.flip_seconds, r.flip_seconds) << " |\n";
  std::printf("\nwrote %s/reach.md\n", o.out.c_str());
}

// Pixels whose camera ray (through the pixel's centre) meets glass first.
std::vector<uint8_t> glass_mask(const Prepared& p, int width, int height) {
  const CameraBasis camera(p.scene.camera_or_auto(), width, height);
  std::vector<uint8_t> mask(size_t(width) * height, 0);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      Hit hit;
      if (p.accel.intersect(camera.ray(x + 0.5f, y + 0.5f), hit))
        mask[size_t(y) * width + x] = p.scene.materials[p.scene.triangle_material[hit.triangle]].type == MaterialType::Glass;
    }
  return mask;
}

void bench_branches(const Prepared& p, const Options& o) {
  const Image ref = read_image(o.ref);
  const std::vector<uint8_t> mask = glass_mask(p, ref.width, ref.height);
  std::ofstream csv(o.out + "/branches.csv");
  csv << "glass_branches,passes,seconds,cpu_seconds,relmse,flip,relmse_glass,flip_glass\n";
  std::printf("\nglass branches (igi, %d photon paths; 'glass': the pixels that see glass first)\n", o.reach_photons.front());
  for (int passes : {1, 4})
    for (int b : {1, 2, 3, 4, 8}) {
      RenderSettings s = igi_settings(o, o.reach_photons.front());
      s.glass_branches = b;
      const Clock start = Clock::now();
      const OfflineResult r = render_offline(p.context(), s, p.frame(ref.width, ref.height, 1), passes, FrameOptions{});
      const Clock d = Clock::now() - start;
      const FlipMap flip = flip_ldr(tonemap_for_flip(r.image), tonemap_for_flip(ref));
      double e = 0.0, f = 0.0;
      int n = 0;
      for (size_t i = 0; i < mask.size(); ++i) {
        if (!mask[i]) continue;
        ++n;
        f += flip.error[i];
        for (int c = 0; c < 3; ++c) {
          const double diff = r.image.pixels[i][c] - ref.pixels[i][c], v = ref.pixels[i][c];
          e += diff * diff / (v * v + kRelMseEpsilon);
        }
      }
      e /= 3.0 * std::max(1, n);
      f /= std::max(1, n);
      char line[256];
      std::snprintf(line, sizeof line, "%d,%d,%.4f,%.4f,%.6g,%.6g,%.6g,%.6g\n", b, passes, d.wall, d.cpu,
                    rel_mse(r.image, ref), flip.mean(), e, f);
      csv << line;
      std::printf("  B=%d %2d passes  %7.3f s (cpu %7.3f)  relMSE %.5f  FLIP %.4f   glass: relMSE %.5f  FLIP %.4f\n", b,
                  passes, d.wall, d.cpu, rel_mse(r.image, ref), flip.mean(), e, f);
    }
}

int run(const Options& o) {
  fs::create_directories(o.out);
  const Prepared p(load_scene(o.scene));
  if (o.pass) bench_pass(p, o);
  if (o.fps) bench_fps(p, o);
  if (o.reach) bench_reach(p, o);
  if (o.branches) bench_branches(p, o);
  return 0;
}

}  // namespace
}  // namespace igi

int main(int argc, char** argv) {
  return igi::bench::run_main("igi-caustics-bench", [&] { return igi::run(igi::parse(argc, argv)); });
}
