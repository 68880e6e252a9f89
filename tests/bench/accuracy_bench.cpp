// igi-accuracy: error against render time for every method on the accuracy
// suite, all points measured in one run on one machine. Writes CSV rows
//   scene,method,params,seconds,relmse,rmse,flip,rays_per_pixel,cpu_seconds,vpls_seen
// (relMSE with epsilon kRelMseEpsilon = 0.01; FLIP: mean LDR-FLIP at 67 pixels
// per degree of the images tonemapped as the PNG output does; rays of every
// kind over all passes, per pixel; CPU time of the process, all threads;
// vpls_seen: the share of the first pass's VPLs that landed in rooms where the
// camera sees a point (scene/suite_scenes.h suite_room), -1 for pt). Asserts
// nothing; scripts/charts/plot_accuracy.py turns the CSV into charts and headline.md.
//
//   igi-accuracy [--scenes a,b] [--size WxH] [--ref-spp N] [--refs DIR] [--out F.csv] [--quick]
//                [--series pt,igi,ir,caustics,view,draws,lightcuts]
//
// References: pt with --ref-spp samples, cached as
// DIR/<scene>-<w>x<h>-<spp>-<hash of settings>.exr so reruns reuse them.
// Sweeps: pt over samples per pixel; ir and igi over VPL paths per set M and
// progressive passes, the clamp (kClamps: fractions of the mean chord,
// relaxing pass by pass; 0.3 the default), (igi) the discontinuity filter,
// and, for clamped points, bias compensation with kCompensationSamples
// ("bc=on"); lightcuts (default 2 % error) over M, unclamped and at the
// default clamp; on scenes with mirrors or glass, igi with the caustic photon
// map ("igi+caustics", kCausticPhotons photon paths a frame, default radius
// and glass branches, filtered, unclamped and at the default clamp) over
// igi's budgets; "view": igi without light importance (igi-power: lights by
// power, the default before 2026-12-05) and with bidirectional IR on top of
// it (igi-bidir, K = 2 M VPLs kept per set), with anti-aliasing 4, per clamp,
// with and without compensation; "draws": igi with --vpl-draws 1 and 4
// (igi-draws), unclamped and at the default clamp and compensation. Every
// other option is at its default: ir and igi estimate light importance.
// --series picks which of these families run (all by default).
// Unclamped VPL errors have infinite variance: a single seed is one draw of
// a heavy-tailed figure, so each VPL point is the median over three seeds,
// with the median seed's time.
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "bench/bench_scene.h"
#include "image/flip.h"
#include "image/metrics.h"
#include "methods/vpl_method.h"
#include "photons/caustic_settings.h"
#include "render/offline_render.h"
#include "sampling/hash.h"
#include "scene/camera_rays.h"
#include "scene/load_scene.h"
#include "scene/suite_scenes.h"

namespace igi {
namespace {

namespace fs = std::filesystem;

constexpr int kCompensationSamples = 4;  // eye samples per pixel when bc=on
const std::vector<int> kCausticPhotons = {20000, 100000};  // photon paths per frame of the igi+caustics series
// The clamps of the igi series (--clamp: a fraction of the scene's mean chord); the default's alone with --quick.
const std::vector<float> kClamps = {0.0f, 0.1f, 0.3f, 1.0f};
const float kDefaultClamp = RenderSettings{}.clamp;

struct Options {
  std::vector<std::string> scenes = {"cornell", "corner", "rooms", "glossy", "glossy-rough", "large", "glass"};
  int width = 128, height = 96;
  int ref_spp = 4096;
  std::string refs = "results/refs";
  std::string out = "results/accuracy/accuracy.csv";
  bool quick = false;  // fewer points, for a smoke run
  std::vector<std::string> series = {"pt", "igi", "ir", "caustics", "view", "draws", "lightcuts"};
  bool runs(const std::string& family) const { return std::find(series.begin(), series.end(), family) != series.end(); }
};

void declare(CLI::App& app, Options& o) {
  app.add_option("--scenes", o.scenes, "scenes, comma-separated")->delimiter(',')->type_name("a,b");
  cli::add_size_option(app, "--size", o.width, o.height, 16384, "image size [128x96]");
  app.add_option("--ref-spp", o.ref_spp, "pt reference samples per pixel [4096]")->check(cli::integer(1, 1 << 24));
  app.add_option("--refs", o.refs, "folder of cached references [results/refs]");
  app.add_option("--out", o.out, "CSV file [results/accuracy/accuracy.csv]");
  app.add_flag("--quick", o.quick, "fewer points, for a smoke run");
  app.add_option("--series", o.series, "of pt,igi,ir,caustics,view,draws,lightcuts [all]")->delimiter(',')
      ->check(cli::one_of({"pt", "igi", "ir", "caustics", "view", "draws", "lightcuts"}));
}

Options parse(int argc, char** argv) {
  return bench::parse_options<Options>("igi-accuracy: error against render time for every method (see the header "
                                       "of tests/bench/accuracy_bench.cpp)", "igi-accuracy", argc, argv, declare);
}

// A scene with its BVH and lights, and its name as on the command line
// (suite_room() knows rooms by it), alive for one scene's sweep.
struct Prepared : bench::PreparedScene {
  std::string name;
  Prepared(std::string n, Scene s) : PreparedScene(std::move(s)), name(std::move(n)) {}
};

double cpu_seconds() {
  timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

FrameSetup base_frame(const Prepared& p, const Options& o, uint32_t seed) {
  FrameSetup frame;
  frame.camera = p.scene.camera_or_auto();
  frame.width = o.width;
  frame.height = o.height;
  frame.seed = seed;
  return frame;
}

OfflineResult render(const Prepared& p, const RenderSettings& settings, const Options& o, int samples,
                     uint32_t seed, double* cpu = nullptr) {
  const double cpu0 = cpu_seconds();
  OfflineResult r = render_offline(p.context(), settings, base_frame(p, o, seed), samples, FrameOptions{});
  if (cpu) *cpu = cpu_seconds() - cpu0;
  return r;
}

// Share of the VPLs of the frame with `seed` in rooms where the camera sees a
// point (through a 32 x 32 grid of pixel centres).
double vpls_seen(const Prepared& p, const RenderSettings& settings, const Options& o, uint32_t seed) {
  const FrameSetup frame = base_frame(p, o, seed);
  const CameraBasis camera(frame.camera, frame.width, frame.height);
  std::vector<int> rooms;
  for (int j = 0; j < 32; ++j)
    for (int i = 0; i < 32; ++i) {
      Ray ray = camera.ray((i + 0.5f) * float(frame.width) / 32.0f, (j + 0.5f) * float(frame.height) / 32.0f);
      ray.mask = kCameraRayMask;
      Hit hit;
      if (p.accel.intersect(ray, hit)) rooms.push_back(suite_room(p.name, ray.origin + hit.t * ray.direction));
    }
  VplMethod method(p.context(), settings);
  method.begin_frame(frame);
  size_t seen = 0;
  for (const Vpl& v : method.vpls().vpls)
    seen += std::find(rooms.begin(), rooms.end(), suite_room(p.name, v.position)) != rooms.end();
  return method.vpls().vpls.empty() ? 0.0 : double(seen) / double(method.vpls().vpls.size());
}

const Image& cached_reference(const Prepared& p, const std::string& name, const Options& o, Image& storage) {
  RenderSettings pt;
  pt.method = MethodKind::PathTracer;
  const uint32_t seed = 7;
  const uint32_t settings_hash = hash(hash(uint32_t(pt.path_depth), seed), 2u /* pt reference version: 2 = unbounded paths */);
  char file[256];
  std::snprintf(file, sizeof file, "%s-%dx%d-%d-%08x.exr", name.c_str(), o.width, o.height, o.ref_spp, settings_hash);
  const fs::path path = fs::path(o.refs) / file;
  if (fs::exists(path)) {
    storage = read_image(path.string());
    std::fprintf(stderr, "%s: reference %s (cached)\n", name.c_str(), path.c_str());
    return storage;
  }
  fs::create_directories(o.refs);
  const OfflineResult r = render(p, pt, o, o.ref_spp, seed);
  write_image(r.image, path.string());
  std::fprintf(stderr, "%s: reference %s (%.1f s)\n", name.c_str(), path.c_str(), r.seconds);
  storage = r.image;
  return storage;
}

struct Point {
  double seconds, relmse, rmse, flip, rays_per_pixel, cpu_seconds = 0.0, vpls_seen = -1.0;
};

Point measure(const OfflineResult& r, const Image& ref, double cpu = 0.0) {
  const double pixels = double(r.image.width) * r.image.height;
  return {r.seconds, rel_mse(r.image, ref), rmse(r.image, ref), mean_flip(r.image, ref), double(r.rays.total()) / pixels,
          cpu};
}

void write_row(std::ofstream& csv, const std::string& scene, const char* method, const std::string& params,
               const Point& p) {
  char line[512];
  std::snprintf(line, sizeof line, "%s,%s,%s,%.4f,%.6g,%.6g,%.6g,%.1f,%.4f,%.4f\n", scene.c_str(), method,
                params.c_str(), p.seconds, p.relmse, p.rmse, p.flip, p.rays_per_pixel, p.cpu_seconds, p.vpls_seen);
  csv << line;
  csv.flush();
  std::fputs(line, stderr);
}

void sweep_pt(const Prepared& p, const std::string& name, const Options& o, const Image& ref, std::ofstream& csv) {
  RenderSettings pt;
  pt.method = MethodKind::PathTracer;
  const int max_spp = o.quick ? 16 : std::max(16, o.ref_spp / 16);
  for (int spp = 1; spp <= max_spp; spp *= 2) {
    double cpu = 0.0;
    const OfflineResult r = render(p, pt, o, spp, 1, &cpu);  // seed 1: independent of the reference's seed 7
    write_row(csv, name, "pt", "spp=" + std::to_string(spp), measure(r, ref, cpu));
  }
}

// Median over three seeds by relMSE (the other figures from the same run).
Point median_point(const Prepared& p, const RenderSettings& s, const Options& o, int passes, const Image& ref) {
  std::vector<Point> points;
  for (uint32_t seed : {1u, 1001u, 2001u}) {
    double cpu = 0.0;
    const OfflineResult r = render(p, s, o, passes, seed, &cpu);
    points.push_back(measure(r, ref, cpu));
    if (s.method != MethodKind::PathTracer && s.method != MethodKind::Lightcuts) points.back().vpls_seen = vpls_seen(p, s, o, seed);
  }
  std::sort(points.begin(), points.end(), [](const Point& a, const Point& b) { return a.relmse < b.relmse; });
  return points[1];
}

// The method column: igi, ir, or igi with the view's options.
std::string method_label(const RenderSettings& s) {
  if (s.vpl_draws > 0) return "igi-draws";
  if (s.bidir_vpls > 0) return "igi-bidir";
  if (s.method == MethodKind::Igi && s.importance_paths == 0) return "igi-power";
  return method_name(s.method);
}

// One VPL series: every budget at one (method, filter, clamp, compensation, anti-aliasing).
// With bidirectional IR (s.bidir_vpls > 0) each budget keeps K = 2 M VPLs per set.
void sweep_budgets(const Prepared& p, const std::string& name, const Options& o, const Image& ref,
                   RenderSettings s, std::ofstream& csv) {
  // (paths per set M, progressive passes): VPL budget up, then passes up.
  std::vector<std::pair<int, int>> budgets = {{1, 1}, {4, 1}, {16, 1}, {64, 1}, {16, 4}, {16, 16}};
  if (o.quick) budgets = {{4, 1}, {8, 1}, {8, 4}};
  const bool ir = s.method == MethodKind::InstantRadiosity;
  for (auto [m, passes] : budgets) {
    // ir shades every VPL per pixel: its big budgets cost N^2 times igi's.
    if (ir && m * passes > 64) continue;
    if (m < s.aa_samples) continue;  // each sub-sample needs a group of paths
    s.paths_per_set = m;
    if (s.bidir_vpls > 0) s.bidir_vpls = 2 * m;
    char params[200];
    std::snprintf(params, sizeof params, "M=%d;passes=%d;clamp=%g;filter=%s;bc=%s;aa=%d;imp=%d;bidir=%d", m, passes,
                  s.clamp, !ir && s.filter ? "on" : "off", s.compensation_samples > 0 ? "on" : "off", s.aa_samples,
                  s.importance_paths, s.bidir_vpls);
    if (s.caustics)
      std::snprintf(params + std::strlen(params), sizeof params - std::strlen(params), ";photons=%d",
                    s.caustic_photons);
    if (s.vpl_draws > 0)
      std::snprintf(params + std::strlen(params), sizeof params - std::strlen(params), ";draws=%d", s.vpl_draws);
    write_row(csv, name, method_label(s).c_str(), params, median_point(p, s, o, passes, ref));
  }
}

// The view's options against igi's default light importance: lights by
// power, and bidirectional IR on top of importance, at anti-aliasing 4 (the
// default), per clamp, compensation on where a clamp cut something.
void sweep_view(const Prepared& p, const std::string& name, const Options& o, const Image& ref, std::ofstream& csv) {
  const std::vector<float> clamps = o.quick ? std::vector<float>{kDefaultClamp} : std::vector<float>{0.1f, 0.3f, 1.0f};
  for (float clamp : clamps)
    for (int compensation : {0, kCompensationSamples}) {
      if (o.quick && compensation > 0) continue;
      for (auto [by_power, bidir] : {std::pair{true, 0}, std::pair{false, 1}}) {
        RenderSettings s;
        s.method = MethodKind::Igi;
        s.clamp = clamp;
        s.compensation_samples = compensation;
        s.aa_samples = 4;
        if (by_power) s.importance_paths = 0;
        s.bidir_vpls = bidir;  // sweep_budgets sets K = 2 M
        sweep_budgets(p, name, o, ref, s, csv);
      }
    }
}

// VPLs drawn from a light tree (--vpl-draws K), at the default clamp,
// compensation and anti-aliasing, unclamped too.
void sweep_draws(const Prepared& p, const std::string& name, const Options& o, const Image& ref, std::ofstream& csv) {
  const RenderSettings defaults;
  for (float clamp : o.quick ? std::vector<float>{defaults.clamp} : std::vector<float>{0.0f, defaults.clamp})
    for (int k : o.quick ? std::vector<int>{1} : std::vector<int>{1, 4}) {
      RenderSettings s;
      s.method = MethodKind::Igi;
      s.clamp = clamp;
      s.compensation_samples = clamp > 0.0f ? defaults.compensation_samples : 0;
      s.vpl_draws = k;
      sweep_budgets(p, name, o, ref, s, csv);
    }
}

// The series: igi over clamps, compensation and anti-aliasing with the
// filter, a few without it, and ir (slow: one clamp pair).
void sweep_vpl(const Prepared& p, const std::string& name, const Options& o, const Image& ref, std::ofstream& csv) {
  const std::vector<float> clamps = o.quick ? std::vector<float>{0.0f, kDefaultClamp} : kClamps;
  auto series = [&](MethodKind kind, bool filter, float clamp, int compensation, int aa) {
    RenderSettings s;
    s.method = kind;
    s.clamp = clamp;
    s.filter = filter;
    s.compensation_samples = compensation;
    s.aa_samples = aa;
    sweep_budgets(p, name, o, ref, s, csv);
  };
  if (o.runs("igi")) {
    for (float clamp : clamps)
      for (int aa : {1, 4}) {
        series(MethodKind::Igi, true, clamp, 0, aa);
        // Bias compensation (Kollig and Keller) only where a clamp cut something.
        if (clamp > 0.0f) series(MethodKind::Igi, true, clamp, kCompensationSamples, aa);
      }
    series(MethodKind::Igi, false, 0.0f, 0, 1);
    series(MethodKind::Igi, false, kDefaultClamp, 0, 1);
  }
  if (o.runs("ir")) {
    series(MethodKind::InstantRadiosity, true, 0.0f, 0, 1);
    series(MethodKind::InstantRadiosity, true, kDefaultClamp, 0, 1);
  }
  // The caustic photon map where there are mirrors or glass to make caustics.
  if (!photons::has_specular_surfaces(p.scene, RenderSettings{}.glossy_threshold) || !o.runs("caustics")) return;
  for (int photons : o.quick ? std::vector<int>{kCausticPhotons.front()} : kCausticPhotons)
    for (float clamp : {0.0f, kDefaultClamp}) {
      RenderSettings s;
      s.method = MethodKind::Igi;
      s.clamp = clamp;
      s.caustics = true;
      s.caustic_photons = photons;
      sweep_budgets(p, name, o, ref, s, csv);
    }
}

// Lightcuts' cost grows slowly with the VPL count, so its budgets go further than ir's.
void sweep_lightcuts(const Prepared& p, const std::string& name, const Options& o, const Image& ref,
                     std::ofstream& csv) {
  const std::vector<int> budgets = o.quick ? std::vector<int>{8, 64} : std::vector<int>{4, 16, 64, 256, 1024};
  for (float clamp : {0.0f, kDefaultClamp})
    for (int m : budgets) {
      RenderSettings s;
      s.method = MethodKind::Lightcuts;
      s.paths_per_set = m;
      s.clamp = clamp;
      char params[128];
      std::snprintf(params, sizeof params, "M=%d;passes=1;clamp=%g;filter=off;bc=off", m, clamp);
      write_row(csv, name, "lightcuts", params, median_point(p, s, o, 1, ref));
    }
}

int run(const Options& o) {
  fs::create_directories(fs::path(o.out).parent_path().empty() ? fs::path(".") : fs::path(o.out).parent_path());
  std::ofstream csv(o.out);
  if (!csv) throw std::runtime_error(o.out + ": cannot write");
  csv << "scene,method,params,seconds,relmse,rmse,flip,rays_per_pixel,cpu_seconds,vpls_seen\n";
  for (const std::string& name : o.scenes) {
    const Prepared p(name, load_scene(name));
    Image storage;
    const Image& ref = cached_reference(p, name, o, storage);
    if (o.runs("pt")) sweep_pt(p, name, o, ref, csv);
    sweep_vpl(p, name, o, ref, csv);
    if (o.runs("view")) sweep_view(p, name, o, ref, csv);
    if (o.runs("draws")) sweep_draws(p, name, o, ref, csv);
    if (o.runs("lightcuts")) sweep_lightcuts(p, name, o, ref, csv);
  }
  std::fprintf(stderr, "wrote %s\n", o.out.c_str());
  return 0;
}

}  // namespace
}  // namespace igi

int main(int argc, char** argv) {
  return igi::bench::run_main("igi-accuracy", [&] { return igi::run(igi::parse(argc, argv)); });
}
