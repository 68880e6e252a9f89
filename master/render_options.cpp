#include "render_options.h"

#include <cmath>
#include <stdexcept>

#include "lightcuts/lightcuts_settings.h"
#include "photons/caustic_settings.h"
#include "scene/builtin_scenes.h"

namespace igi {
namespace {

int to_int(const std::string& option, const std::string& value, int min_value) {
  size_t end = 0;
  int v = 0;
  try { v = std::stoi(value, &end); } catch (const std::exception&) { end = 0; }
  if (end != value.size() || value.empty() || v < min_value)
    throw std::invalid_argument(option + ": expected an integer >= " + std::to_string(min_value) + ", got '" + value + "'");
  return v;
}

// Any number, range-checked by the caller (lightcuts_settings.h).
float to_number(const std::string& option, const std::string& value) {
  size_t end = 0;
  float v = 0;
  try { v = std::stof(value, &end); } catch (const std::exception&) { end = 0; }
  if (end != value.size() || value.empty() || !std::isfinite(v))
    throw std::invalid_argument(option + ": expected a number, got '" + value + "'");
  return v;
}

float to_float(const std::string& option, const std::string& value) {
  size_t end = 0;
  float v = 0;
  try { v = std::stof(value, &end); } catch (const std::exception&) { end = 0; }
  if (end != value.size() || value.empty() || !(v >= 0.0f))
    throw std::invalid_argument(option + ": expected a non-negative number, got '" + value + "'");
  return v;
}

void parse_size(const std::string& value, RenderOptions& o) {
  size_t x = value.find('x');
  if (x == std::string::npos) throw std::invalid_argument("--size: expected WxH, got '" + value + "'");
  o.width = to_int("--size", value.substr(0, x), 1);
  o.height = to_int("--size", value.substr(x + 1), 1);
}

// Before any work: options lightcuts cannot use, and VPL counts that would not fit in memory.
void check_lightcuts(const RenderSettings& s) {
  if (s.method != MethodKind::Lightcuts) return;
  std::string error = lightcuts::settings_error(s);
  if (error.empty()) error = lightcuts::memory_error(s, lightcuts::physical_memory_bytes());
  if (!error.empty()) throw std::invalid_argument(error);
}

// Before any work: a caustic map that could not fit in memory.
void check_caustics(const RenderSettings& s) {
  if (!s.caustics) return;
  if (s.method != MethodKind::InstantRadiosity && s.method != MethodKind::Igi)
    throw std::invalid_argument("--caustics: only the ir and igi methods add caustic photons (pt finds caustics "
                                "by itself), got --method " + std::string(method_name(s.method)));
  const std::string error = photons::memory_error(s, lightcuts::physical_memory_bytes());
  if (!error.empty()) throw std::invalid_argument(error);
}

}  // namespace

std::string render_usage(const std::string& program) {
  std::string scenes;
  for (const std::string& n : builtin_scene_names()) scenes += " " + n;
  return "usage: " + program + " [options]\n"
         "  --scene NAME|FILE     built-in scene (" + scenes + " ) or .gltf/.glb file [cornell]\n"
         "  --method pt|ir|igi|lightcuts  rendering method [igi]\n"
         "  --spp N               pt: samples per pixel; ir/igi: passes with fresh VPLs [1]\n"
         "  --size WxH            image size [640x480]\n"
         "  -o FILE               output image: .exr/.hdr linear, .png sRGB [render.png]\n"
         "  --exposure E          scale before writing PNG [1]\n"
         "  --threads T           render threads, 0 = all [0]\n"
         "  --tile T              tile size in pixels [32]\n"
         "  --seed S              frame seed [1]\n"
         "  --path-depth D        pt: longest path in bounces, 0 = unbounded (Russian roulette) [0]\n"
         "  --light-depth D       ir/igi: longest VPL light path, 0 = unbounded (Russian roulette) [0]\n"
         "  --specular-depth D    ir/igi: mirrors and glass followed from the camera, 0 = unbounded [16]\n"
         "  --vpl-sets N          ir/igi: N x N interleaved VPL sets [3]\n"
         "  --vpl-paths M         ir/igi: light paths per VPL set [16]\n"
         "  --aa S                ir/igi: S sub-samples per pixel (1, 4, 9, ...), each shaded by 1/S of the\n"
         "                        pixel's light paths (anti-aliasing by VPL groups); needs M >= S [1]\n"
         "  --glossy-threshold A  ir/igi: GGX surfaces with alpha below A gather their lobe with rays\n"
         "                        instead of VPL light; 0 = VPLs shade every glossy surface [0.2]\n"
         "  --glossy-rays K       ir/igi: gather rays per sub-sample of such a surface [1]\n"
         "  --clamp C             ir/igi: clamp 1/r^2 below distance C x scene diagonal, 0 = off [0]\n"
         "  --compensate N        ir/igi: bias compensation, N eye samples per pixel (needs --clamp), 0 = off [0]\n"
         "  --no-filter           igi: skip the discontinuity buffer\n"
         "  --filter-normal C     igi: neighbours need normal dot above C [0.9]\n"
         "  --filter-depth R      igi: neighbours need relative depth difference below R [0.05]\n"
         "  --glass-branches B    ir/igi: glass seen from the camera splits into reflection and refraction at its\n"
         "                        first B - 1 surfaces, each branch filtered on its own; 1 = pick one by Fresnel [3]\n"
         "  --caustics            ir/igi: add caustics from a photon map (light through mirrors and glass)\n"
         "  --caustic-photons N   ir/igi: photon paths shot per frame, >= 1; implies --caustics [20000]\n"
         "  --caustic-radius R    ir/igi: photon gather radius, a fraction of the scene diagonal; implies\n"
         "                        --caustics [0.01]\n"
         "  --lightcuts-error E   lightcuts (over all --vpl-sets x --vpl-paths VPLs): refine until every cluster's\n"
         "                        error bound is below E x the pixel's total, 0 < E < 1 [0.02]\n"
         "  --lightcuts-max-cut N lightcuts: at most N nodes (shadow rays) in a cut [1000]\n"
         "  --lightcuts-spacing S lightcuts: reconstruction cuts, full cuts every S pixels only, 0 = off [0]\n"
         "  --lightcuts-samples K lightcuts: K = 1, 4, 9 ... 64 gather points per pixel (multidimensional) [1]\n"
         "  --importance N        ir/igi: start VPL light paths at lights by their estimated share of the image,\n"
         "                        from N camera paths (light importance for the view), 0 = by power [0]\n"
         "  --importance-floor F  ir/igi: share of light paths still started by power, 0..1 [0.2]\n"
         "  --bidir K             ir/igi: bidirectional instant radiosity: per set, keep K of the VPLs of\n"
         "                        --vpl-paths light paths and R camera paths, by their estimated contribution [0]\n"
         "  --bidir-camera-paths R  ir/igi with --bidir: camera paths per set, 0 = --vpl-paths [0]\n"
         "  --export-gltf FILE    write the scene as glTF and exit\n"
         "  --quiet               no progress output\n"
         "  --show                show the result in a window (Esc closes it)\n"
         "  --screenshot FILE     show, save the window's pixels to FILE, close\n";
}

RenderOptions parse_render_options(const std::vector<std::string>& args) {
  RenderOptions o;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&]() -> const std::string& {
      if (i + 1 >= args.size()) throw std::invalid_argument(a + ": missing value");
      return args[++i];
    };
    RenderSettings& s = o.settings;
    if (a == "--help" || a == "-h") o.help = true;
    else if (a == "--scene") o.scene = value();
    else if (a == "--method") {
      auto m = parse_method(value());
      if (!m) throw std::invalid_argument("--method: expected pt, ir, igi or lightcuts, got '" + args[i] + "'");
      s.method = *m;
    }
    else if (a == "--spp") o.samples = to_int(a, value(), 1);
    else if (a == "--size") parse_size(value(), o);
    else if (a == "-o" || a == "--output") o.output = value();
    else if (a == "--exposure") o.exposure = to_float(a, value());
    else if (a == "--threads") o.threads = to_int(a, value(), 0);
    else if (a == "--tile") o.tile_size = to_int(a, value(), 1);
    else if (a == "--seed") o.seed = uint32_t(to_int(a, value(), 0));
    else if (a == "--path-depth") s.path_depth = to_int(a, value(), 0);
    else if (a == "--light-depth") s.light_depth = to_int(a, value(), 0);
    else if (a == "--specular-depth") s.specular_depth = to_int(a, value(), 0);
    else if (a == "--max-depth")
      throw std::invalid_argument("--max-depth was split: --path-depth (pt), --light-depth (VPL light paths) and "
                                  "--specular-depth (mirrors and glass from the camera)");
    else if (a == "--vpl-sets") s.interleave = to_int(a, value(), 1);
    else if (a == "--vpl-paths") s.paths_per_set = to_int(a, value(), 1);
    else if (a == "--aa") s.aa_samples = to_int(a, value(), 1);
    else if (a == "--glossy-threshold") s.glossy_threshold = to_float(a, value());
    else if (a == "--glossy-rays") s.glossy_rays = to_int(a, value(), 1);
    else if (a == "--clamp") s.clamp = to_float(a, value());
    else if (a == "--compensate") s.compensation_samples = to_int(a, value(), 0);
    else if (a == "--no-filter") s.filter = false;
    else if (a == "--filter-normal") s.filter_normal_cos = to_float(a, value());
    else if (a == "--filter-depth") s.filter_depth_ratio = to_float(a, value());
    else if (a == "--glass-branches") s.glass_branches = to_int(a, value(), 1);
    else if (a == "--caustics") s.caustics = true;
    else if (a == "--caustic-photons") { s.caustic_photons = to_int(a, value(), 0); s.caustics = true; }
    else if (a == "--caustic-radius") { s.caustic_radius = to_float(a, value()); s.caustics = true; }
    else if (a == "--lightcuts-error") s.lightcuts_error = to_number(a, value());
    else if (a == "--lightcuts-max-cut") s.lightcuts_max_cut = to_int(a, value(), 1);
    else if (a == "--lightcuts-spacing") s.lightcuts_spacing = to_int(a, value(), 0);
    else if (a == "--lightcuts-samples") s.lightcuts_samples = to_int(a, value(), 1);
    else if (a == "--importance") s.importance_paths = to_int(a, value(), 0);
    else if (a == "--importance-floor") s.importance_floor = to_float(a, value());
    else if (a == "--bidir") s.bidir_vpls = to_int(a, value(), 0);
    else if (a == "--bidir-camera-paths") s.bidir_camera_paths = to_int(a, value(), 0);
    else if (a == "--export-gltf") o.export_gltf = value();
    else if (a == "--quiet") o.quiet = true;
    else if (a == "--show") o.show = true;
    else if (a == "--screenshot") { o.show = true; o.screenshot = value(); }
    else throw std::invalid_argument("unknown option '" + a + "' (see --help)");
  }
  if (auto error = settings_error(o.settings)) throw std::invalid_argument(*error);
  check_lightcuts(o.settings);
  check_caustics(o.settings);
  return o;
}

}  // namespace igi
