// igi-lightcuts-bench: Lightcuts against ir over exactly the same VPLs, and
// both against a converged path-traced reference. Prints and writes CSV rows
//   scene,vpls,paths_per_set,method,seconds,cpu_seconds,frame_setup_seconds,
//   shadow_rays_per_pixel,cut_nodes_per_pixel,reconstructed,rel_mse_ir,rel_mse_pt,
//   mean_rel_diff_ir,within_2pct_ir,flip_ir,flip_pt,flip_plain
// (reconstructed: the share of pixels shaded from the sample grid; flip_plain:
// FLIP of a variant against plain lightcuts over the same VPLs).
// Asserts nothing; scripts/bench-lightcuts.sh runs it and draws the chart.
//
//   igi-lightcuts-bench [--scenes a,b] [--vpls 1000,10000,100000] [--size WxH]
//                       [--ref-spp N] [--refs DIR] [--out F.csv] [--spacing S]
//                       [--samples K] [--frames F] [--clamp C] [--no-ir] [--no-per-pixel]
//
// VPL counts: for each target the bench traces a pilot frame to learn the
// scene's VPLs per light path, then picks M (N x N sets) to land near it; the
// row gives the count reached. Methods: ir (one sample a pixel, no
// compensation), lightcuts (plain cuts at the defaults: block cuts of 4 x 4),
// lightcuts-pixel (a cut per pixel, --lightcuts-block 0; --no-per-pixel
// leaves it out), lightcuts-rc (reconstruction cuts, --spacing), lightcuts-md (K gather
// points per pixel, --samples; 0 leaves it out). Seconds are medians over F
// frames of the whole frame: VPL generation and light tree (frame_setup) plus
// the tiles, on all threads; cpu_seconds is the CPU time the process got.
// ir over 50,000 VPLs or more renders one frame only (it is slow).
// Per-pixel relative difference to ir: |Y - Y_ir| / Y_ir of luminance Y,
// over pixels with Y_ir above 1 % of the image's mean.
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
#include "lightcuts/lightcuts_method.h"
#include "render/frame_renderer.h"
#include "render/offline_render.h"
#include "sampling/hash.h"
#include "scene/load_scene.h"
#include "vpl/vpl_generator.h"

namespace igi {
namespace {

using bench::Clock;

namespace fs = std::filesystem;

struct Options {
  std::vector<std::string> scenes = {"cornell", "cornell-blob", "rooms-4"};
  std::vector<int> vpls = {1000, 10000, 100000};
  int width = 96, height = 72;
  int ref_spp = 1024;
  std::string refs = "results/refs";
  std::string out = "results/lightcuts/lightcuts.csv";
  int spacing = 4;
  int samples = 4;
  int frames = 1;
  float clamp = 0.0f;
  bool ir = true;
  bool per_pixel = true;
};

void declare(CLI::App& app, Options& o) {
  app.add_option("--scenes", o.scenes, "scenes, comma-separated")->delimiter(',')->type_name("a,b");
  app.add_option("--vpls", o.vpls, "VPL counts to aim at [1000,10000,100000]")->delimiter(',')
      ->check(cli::integer(1, 1 << 26));
  cli::add_size_option(app, "--size", o.width, o.height, 16384, "image size [96x72]");
  app.add_option("--ref-spp", o.ref_spp, "pt reference samples per pixel [1024]")->check(cli::integer(1, 1 << 24));
  app.add_option("--refs", o.refs, "folder of cached references [results/refs]");
  app.add_option("--out", o.out, "CSV file [results/lightcuts/lightcuts.csv]");
  app.add_option("--spacing", o.spacing, "reconstruction cuts' spacing [4]")->check(cli::integer(0, 64));
  app.add_option("--samples", o.samples, "multidimensional gather points, 0 = leave out [4]")
      ->check(cli::integer(0, 64));
  app.add_option_function<int>("--frames", [&o](int f) { o.frames = std::max(1, f); }, "frames, median [1]")
      ->check(cli::integer(0, 100000));
  app.add_option("--clamp", o.clamp, "clamp [0]")->check(cli::non_negative_number());
  app.add_flag_callback("--no-ir", [&o] { o.ir = false; }, "leave out ir");
  app.add_flag_callback("--no-per-pixel", [&o] { o.per_pixel = false; }, "leave out lightcuts-pixel");
}

Options parse(int argc, char** argv) {
  return bench::parse_options<Options>("igi-lightcuts-bench: Lightcuts against ir over the same VPLs (see the "
                                       "header of tests/bench/lightcuts_bench.cpp)", "igi-lightcuts-bench", argc,
                                       argv, declare);
}

using Prepared = bench::PreparedScene;

struct Run {
  Image image;
  double seconds = 0, cpu = 0, setup = 0;
  RayCounts rays;
  double cut_nodes = 0;
  double reconstructed = 0;  // pixels shaded with the samples' visibility
};

Run run(const Prepared& p, const RenderSettings& s, const Options& o, int frames) {
  auto method = make_method(p.context(), s);
  const FrameSetup frame = p.frame(o.width, o.height);
  std::vector<Run> runs;
  for (int f = 0; f < frames; ++f) {
    Run r;
    const Clock start = Clock::now();
    method->begin_frame(frame);
    r.setup = (Clock::now() - start).wall;
    r.image = render_frame(*method, frame, tile_border(s), FrameOptions{}, r.rays);
    const Clock d = Clock::now() - start;
    r.seconds = d.wall;
    r.cpu = d.cpu;
    if (auto* lc = dynamic_cast<const lightcuts::LightcutsMethod*>(method.get())) {
      r.cut_nodes = double(lc->stats().cut_nodes);
      r.reconstructed = double(lc->stats().reconstructed);
    }
    runs.push_back(std::move(r));
  }
  std::sort(runs.begin(), runs.end(), [](const Run& a, const Run& b) { return a.seconds < b.seconds; });
  return std::move(runs[runs.size() / 2]);
}

const Image& reference(const Prepared& p, const std::string& name, const Options& o, Image& storage) {
  // The naming of tests/bench/accuracy_bench.cpp, so both share references.
  RenderSettings pt;
  pt.method = MethodKind::PathTracer;
  const uint32_t seed = 7;
  const uint32_t settings_hash = hash(hash(uint32_t(pt.path_depth), seed), 2u /* 2 = unbounded paths */);
  char file[256];
  std::snprintf(file, sizeof file, "%s-%dx%d-%d-%08x.exr", name.c_str(), o.width, o.height, o.ref_spp, settings_hash);
  const fs::path path = fs::path(o.refs) / file;
  if (fs::exists(path)) return storage = read_image(path.string());
  fs::create_directories(o.refs);
  FrameSetup frame = p.frame(o.width, o.height);
  frame.seed = seed;
  storage = render_offline(p.context(), pt, frame, o.ref_spp, FrameOptions{}).image;
  write_image(storage, path.string());
  std::fprintf(stderr, "%s: reference %s\n", name.c_str(), path.c_str());
  return storage;
}

double lum(glm::vec3 c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

// Mean |Y - Y_ir| / Y_ir and the share within 2 %, over pixels above 1 % of the mean.
std::pair<double, double> relative_difference(const Image& image, const Image& ir) {
  const double floor = 0.01 * lum(ir.mean());
  double sum = 0;
  size_t count = 0, within = 0;
  for (size_t i = 0; i < ir.pixels.size(); ++i) {
    const double r = lum(ir.pixels[i]);
    if (!(r > floor)) continue;
    const double d = std::abs(lum(image.pixels[i]) - r) / r;
    sum += d;
    within += d <= 0.02;
    ++count;
  }
  return {count ? sum / double(count) : 0.0, count ? double(within) / double(count) : 1.0};
}

// M for about `target` VPLs in all N x N sets (the default N), from a pilot frame's VPLs per path.
int paths_for(const Prepared& p, int target) {
  RenderSettings s;
  s.paths_per_set = 256;
  const VplSets pilot = generate_vpls(p.context(), s, 1);
  const double per_m = double(pilot.vpls.size()) / 256.0;  // VPLs of all sets per path a set
  return std::max(1, int(std::lround(double(target) / per_m)));
}

void write_row(std::ofstream& csv, const std::string& scene, size_t vpls, int m, const char* method, const Run& r,
               const Image* ir, const Image& pt, const Image* plain) {
  const double pixels = double(r.image.width) * r.image.height;
  double rel_ir = -1, mean_diff = -1, within = -1, flip_ir = -1, flip_plain = -1;
  const double flip_pt = mean_flip(r.image, pt);
  if (ir) {
    rel_ir = rel_mse(r.image, *ir);
    std::tie(mean_diff, within) = relative_difference(r.image, *ir);
    flip_ir = mean_flip(r.image, *ir);
  }
  if (plain) flip_plain = mean_flip(r.image, *plain);
  char line[512];
  std::snprintf(line, sizeof line, "%s,%zu,%d,%s,%.4f,%.4f,%.4f,%.1f,%.1f,%.3f,%.6g,%.6g,%.5f,%.4f,%.5f,%.5f,%.5f\n",
                scene.c_str(), vpls, m, method, r.seconds, r.cpu, r.setup, double(r.rays.shadow) / pixels,
                r.cut_nodes / pixels, r.reconstructed / pixels, rel_ir, rel_mse(r.image, pt), mean_diff, within,
                flip_ir, flip_pt, flip_plain);
  csv << line;
  csv.flush();
  std::fputs(line, stdout);
  std::fflush(stdout);
}

int run_all(const Options& o) {
  fs::create_directories(fs::path(o.out).parent_path().empty() ? fs::path(".") : fs::path(o.out).parent_path());
  std::ofstream csv(o.out);
  if (!csv) throw std::runtime_error(o.out + ": cannot write");
  csv << "scene,vpls,paths_per_set,method,seconds,cpu_seconds,frame_setup_seconds,shadow_rays_per_pixel,"
         "cut_nodes_per_pixel,reconstructed,rel_mse_ir,rel_mse_pt,mean_rel_diff_ir,within_2pct_ir,flip_ir,flip_pt,"
         "flip_plain\n";
  for (const std::string& name : o.scenes) {
    const Prepared p(load_scene(name));
    Image storage;
    const Image& pt = reference(p, name, o, storage);
    for (int target : o.vpls) {
      RenderSettings s;
      s.paths_per_set = paths_for(p, target);
      s.method = MethodKind::Lightcuts;
      s.clamp = o.clamp;
      // One sample a pixel, nothing added: lightcuts has neither anti-aliasing
      // nor compensation, and ir must estimate the same sum to be compared.
      s.aa_samples = 1;
      s.compensation_samples = 0;
      // Light paths by power, no bidirectional resampling: lightcuts takes
      // neither, and ir must shade the very same VPLs.
      s.importance_paths = 0;
      s.bidir_vpls = 0;
      const Run plain = run(p, s, o, o.frames);
      const size_t vpls = generate_vpls(p.context(), s, 1).vpls.size();
      Run ir_run;
      if (o.ir) {
        RenderSettings ir = s;
        ir.method = MethodKind::InstantRadiosity;
        ir_run = run(p, ir, o, target >= 50000 ? 1 : o.frames);
        write_row(csv, name, vpls, s.paths_per_set, "ir", ir_run, nullptr, pt, nullptr);
      }
      const Image* ir_image = o.ir ? &ir_run.image : nullptr;
      write_row(csv, name, vpls, s.paths_per_set, "lightcuts", plain, ir_image, pt, nullptr);
      if (o.per_pixel) {
        RenderSettings per_pixel = s;
        per_pixel.lightcuts_block = 0;
        write_row(csv, name, vpls, s.paths_per_set, "lightcuts-pixel", run(p, per_pixel, o, o.frames), ir_image, pt,
                  &plain.image);
      }
      if (o.spacing > 1) {
        RenderSettings rc = s;
        rc.lightcuts_spacing = o.spacing;
        write_row(csv, name, vpls, s.paths_per_set, "lightcuts-rc", run(p, rc, o, o.frames), ir_image, pt, &plain.image);
      }
      if (o.samples > 1) {
        RenderSettings md = s;
        md.lightcuts_samples = o.samples;
        // Antialiased (K sub-pixel positions): compared with pt only, which antialiases too.
        write_row(csv, name, vpls, s.paths_per_set, "lightcuts-md", run(p, md, o, o.frames), nullptr, pt, nullptr);
      }
    }
  }
  std::fprintf(stderr, "wrote %s\n", o.out.c_str());
  return 0;
}

}  // namespace
}  // namespace igi

int main(int argc, char** argv) {
  return igi::bench::run_main("igi-lightcuts-bench", [&] { return igi::run_all(igi::parse(argc, argv)); });
}
