#include "render_options.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <thread>

#include "cli/option_checks.h"
#include "core/clamp.h"
#include "image/image.h"
#include "methods/memory_check.h"
#include "photons/caustic_settings.h"
#include "protocol/messages.h"
#include "scene/builtin_scenes.h"

namespace igi {
namespace {

using cli::integer;
using cli::OptionError;

// Every default --help shows is read from the structs, never typed twice.
const RenderOptions kDefaults{};

std::string shown_default(const std::string& value) { return " [" + value + "]"; }
std::string shown_default(int value) { return shown_default(std::to_string(value)); }
std::string shown_default(uint32_t value) { return shown_default(std::to_string(value)); }
std::string shown_default(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return shown_default(std::string(text));
}

std::string bidir_text(int k) { return k == kBidirAuto ? "auto" : std::to_string(k); }

constexpr int kMaxSamples = 1 << 20;    // --spp: samples per pixel or passes

// Before any work: VPLs, a light tree or a caustic map that could not fit in this machine's memory,
// and tiles whose scratch could not: igi-render's threads, or the local workers' (every core) under igi-master.
void check_memory(const RenderOptions& o) {
  const uint64_t memory = machine_memory_bytes();
  if (const std::string error = memory_error(o.settings, memory); !error.empty()) throw OptionError(error);
  const int threads = o.threads > 0 ? o.threads : int(std::max(1u, std::thread::hardware_concurrency()));
  if (const std::string error = tile_memory_error(o.settings, o.tile_size, o.tile_size, threads, memory); !error.empty())
    throw OptionError(error);
}

// "auto", or a number that `number_check` accepts.
CLI::Validator auto_or(CLI::Validator number_check) {
  return CLI::Validator(
      [number_check](std::string& text) -> std::string {
        std::string copy = text;
        if (text == "auto" || number_check(copy).empty()) return {};
        return "expected auto or " + number_check(copy).substr(std::string("expected ").size());
      },
      "");
}

// One exposure, given as a factor (--exposure), in stops (--ev: 2^S), or
// metered from each image (auto); the two options are one (check_render_options).
void add_exposure_options(CLI::App& app, RenderOptions& o) {
  const double most = std::exp2(double(kExposureStops));
  auto set = [&o](const std::string& text, bool stops) {
    o.exposure_given = true;
    o.exposure.metered = text == "auto";
    if (!o.exposure.metered) o.exposure.factor = stops ? std::exp2(std::stof(text)) : std::stof(text);
  };
  const CLI::Validator factor(
      [most](std::string& text) -> std::string {
        std::string copy = text;
        if (cli::number()(copy).empty() && std::stod(text) > 0.0 && std::stod(text) <= most) return {};
        char bound[32];
        std::snprintf(bound, sizeof bound, "%g", most);
        return "expected a factor > 0 and <= " + std::string(bound) + ", got '" + text + "'";
      },
      "");
  app.add_option_function<std::string>(
         "--exposure", [set](const std::string& k) { set(k, false); },
         "8-bit outputs (PNG, the window): the image times K before --view; auto: the factor that brings each "
         "image's log-average luminance (of its lit pixels) to middle grey, as a camera's meter [the window: "
         "auto, measured once on opening and again on M; image files: 1]")
      ->check(auto_or(factor))->type_name("K|auto");
  app.add_option_function<std::string>(
         "--ev", [set](const std::string& s) { set(s, true); },
         "--exposure in stops: the image times 2^S (+1 doubles it), S within +-" +
             std::to_string(int(kExposureStops)) + " [0]")
      ->check(auto_or(cli::bounded_number(double(kExposureStops))))->type_name("S|auto");
  app.add_option_function<std::string>(
         "--view", [&o](const std::string& v) { o.view = *parse_view(v); },
         "8-bit outputs: the view transform after the exposure: standard (each channel clipped at white), neutral "
         "(Khronos PBR Neutral: base colours show as themselves, highlights compress towards white), agx (AgX, "
         "Blender's default view: highlights roll off, white 4 stops past where standard clips)" +
             shown_default(std::string(view_name(kDefaults.view))))
      ->check(cli::one_of({"standard", "neutral", "agx"}))->type_name("standard|neutral|agx");
}

void add_image_options(CLI::App& app, RenderOptions& o) {
  std::string scenes;
  for (const std::string& n : builtin_scene_names()) scenes += " " + n;
  app.add_option("--scene", o.scene, "built-in scene (" + scenes + " ) or .gltf/.glb file" + shown_default(kDefaults.scene))
      ->type_name("NAME|FILE");
  app.add_option_function<std::string>(
         "--method", [&o](const std::string& m) { o.settings.method = *parse_method(m); }, "rendering method" + shown_default(std::string(method_name(kDefaults.settings.method))))
      ->check(cli::one_of({"pt", "ir", "igi", "lightcuts"}))->type_name("pt|ir|igi|lightcuts");
  app.add_option("--spp", o.samples, "pt: samples per pixel; ir/igi: passes with fresh VPLs" + shown_default(kDefaults.samples))
      ->check(integer(1, kMaxSamples))->type_name("N");
  cli::add_size_option(app, "--size", o.width, o.height, protocol::kMaxImageSide, "image size" + shown_default(std::to_string(kDefaults.width) + "x" + std::to_string(kDefaults.height)));
  app.add_option("-o,--output", o.output, "output image: .exr/.hdr linear, .png sRGB" + shown_default(kDefaults.output))->type_name("FILE");
  add_exposure_options(app, o);
  app.add_option("--threads", o.threads, "render threads, 0 = all" + shown_default(kDefaults.threads))
      ->check(integer(0, cli::kMaxThreads))->type_name("T");
  app.add_option("--tile", o.tile_size, "tile size in pixels" + shown_default(kDefaults.tile_size))
      ->check(integer(1, protocol::kMaxTileSide))->type_name("T");
  app.add_option("--seed", o.seed, "frame seed" + shown_default(kDefaults.seed))->check(integer<uint32_t>(0, UINT32_MAX))->type_name("S");
  app.add_option("--camera", o.camera_file, "start from this camera (JSON: position, forward, up, vfov_degrees; "
                 "the window's F5 saves one); igi-master's window: also the file F5 and F9 use [camera.json there]")
      ->type_name("FILE");
  app.add_option("--export-gltf", o.export_gltf, "write the scene as glTF and exit")->type_name("FILE");
  app.add_flag("--quiet", o.quiet, "no progress output");
  app.add_flag("--show", o.show, "show the result in a window (Esc closes it)");
  app.add_option_function<std::string>(
         "--screenshot", [&o](const std::string& f) { o.show = true, o.screenshot = f; },
         "show, save the window's pixels to FILE, close")->type_name("FILE");
  app.add_option("--time", o.time, "animated scenes: seconds of animation time of the (first) frame" + shown_default(kDefaults.time))
      ->check(cli::bounded_number(protocol::kMaxSceneTime))->type_name("T");
  cli::add_vec3_option(app, "--move-lights", o.light_offset, 1e6,
                       "metres to move the scene's lights by, as the window's J/L, U/O, I/K keys do [0,0,0]");
  cli::add_sky_option(app, "--environment", o.environment, protocol::kMaxEnvironment,
                      "light the scene with a sky, seen where rays leave the scene: a constant radiance (linear "
                      "RGB; 1,1,1 is white) or an HDR environment map (an equirectangular .exr or .hdr, +y up, "
                      "its middle looking along -z); replaces the scene's own (glTF scene extras "
                      "\"environment\") [none]");
  app.add_option("--environment-scale", o.environment_scale, "--environment's radiance times K [1]")
      ->check(cli::non_negative_number())->check(cli::bounded_number(protocol::kMaxEnvironment))->type_name("K");
  app.add_option("--environment-rotation", o.environment_rotation,
                 "turns --environment's map by DEG degrees about +y (right-handed) [0]")
      ->check(cli::bounded_number(360.0))->type_name("DEG");
  app.add_option_function<std::string>(
         "--light-units",
         [&o](const std::string& u) { o.light_units = u == "radiometric" ? LightUnits::Radiometric : LightUnits::Photometric; },
         "a glTF file's lamps: photometric as glTF and Blender write them (point and spot in candela, sun in lux, "
         "at 683 lm/W), or radiometric (W/sr, W/m^2) [photometric]")
      ->check(cli::one_of({"photometric", "radiometric"}))->type_name("photometric|radiometric");
}

void add_vpl_options(CLI::App& app, RenderSettings& s) {
  app.add_option("--path-depth", s.path_depth, "pt: longest path in bounces, 0 = unbounded (Russian roulette)" + shown_default(kDefaults.settings.path_depth))
      ->check(integer<int>())->type_name("D");
  app.add_option("--light-depth", s.light_depth, "ir/igi: longest VPL light path, 0 = unbounded (Russian roulette)" + shown_default(kDefaults.settings.light_depth))
      ->check(integer<int>())->type_name("D");
  app.add_option("--specular-depth", s.specular_depth,
                 "ir/igi: mirrors and glass followed from the camera, 0 = unbounded" + shown_default(kDefaults.settings.specular_depth))
      ->check(integer<int>())->type_name("D");
  app.add_option("--max-depth")->group("");  // split: refused with a message that says how
  app.add_option("--vpl-sets", s.interleave, "ir/igi: N x N interleaved VPL sets" + shown_default(kDefaults.settings.interleave))
      ->check(integer<int>())->type_name("N");
  app.add_option("--vpl-paths", s.paths_per_set, "ir/igi: light paths per VPL set" + shown_default(kDefaults.settings.paths_per_set))
      ->check(integer<int>())->type_name("M");
  app.add_option("--vpl-draws", s.vpl_draws, "ir/igi: each shading point draws K VPLs of all N x N sets from a "
                 "light tree by their bound, one shadow ray each (stochastic lightcuts), instead of its set's; 0 = sets" +
                 shown_default(kDefaults.settings.vpl_draws))
      ->check(integer<int>())->type_name("K");
  app.add_option("--aa", s.aa_samples, "ir/igi: S sub-samples per pixel (1, 4, 9, ...), each shaded by 1/S of the "
                 "pixel's light paths (anti-aliasing by VPL groups); needs --vpl-paths >= S" + shown_default(kDefaults.settings.aa_samples))
      ->check(integer<int>())->type_name("S");
  app.add_option("--glossy-threshold", s.glossy_threshold, "ir/igi: GGX surfaces with alpha below A gather their "
                 "lobe with rays instead of VPL light; 0 = VPLs shade every glossy surface" + shown_default(kDefaults.settings.glossy_threshold))
      ->check(cli::number())->type_name("A");
  app.add_option("--glossy-rays", s.glossy_rays, "ir/igi: gather rays per sub-sample of such a surface" + shown_default(kDefaults.settings.glossy_rays))
      ->check(integer<int>())->type_name("K");
  app.add_option("--clamp", s.clamp, "ir/igi/lightcuts: clamp 1/r^2 below distance C x the scene's mean chord (about "
                 "a room); pass k of --spp clamps at C / (k + 1)^(1/4) of it, so passes converge; 0 = off, at most "
                 + std::to_string(int(kMaxClamp)) + shown_default(kDefaults.settings.clamp))
      ->check(cli::number())->type_name("C");
  app.add_option("--compensate", s.compensation_samples,
                 "ir/igi: bias compensation, N eye samples per pixel (needs --clamp), 0 = off" + shown_default(kDefaults.settings.compensation_samples))
      ->check(integer<int>())->type_name("N");
  app.add_option("--glass-branches", s.glass_branches, "ir/igi: glass seen from the camera splits into reflection "
                 "and refraction at its first B - 1 surfaces, each branch filtered on its own; 1 = pick one by "
                 "Fresnel" + shown_default(kDefaults.settings.glass_branches))->check(integer<int>())->type_name("B");
}

void add_filter_and_caustic_options(CLI::App& app, RenderOptions& o) {
  RenderSettings& s = o.settings;
  app.add_flag_callback("--no-filter", [&s] { s.filter = false; }, "igi: skip the discontinuity buffer");
  app.add_option("--filter-normal", s.filter_normal_cos, "igi: neighbours need normal dot above C" + shown_default(kDefaults.settings.filter_normal_cos))
      ->check(cli::number())->type_name("C");
  app.add_option("--filter-depth", s.filter_depth_ratio,
                 "igi: neighbours need relative depth difference below R" + shown_default(kDefaults.settings.filter_depth_ratio))
      ->check(cli::number())->type_name("R");
  app.add_option("--wavelet", s.wavelet_levels,
                 "ir/igi: levels of the edge-avoiding wavelet filter after the discontinuity buffer (smooths one "
                 "pass; a tile's border grows by 2^(L+1), so larger --tile costs less); 0 = off" +
                     shown_default(kDefaults.settings.wavelet_levels))
      ->check(integer<int>())->type_name("L");
  app.add_flag_callback("--caustics", [&o] { o.settings.caustics = o.caustics_given = true; },
                        "ir/igi: add caustics from a photon map (light through mirrors, glass and GGX sharper "
                        "than --glossy-threshold); the default where the scene has them");
  app.add_flag_callback("--no-caustics", [&o] { o.settings.caustics = false, o.caustics_given = true; },
                        "ir/igi: no caustics, even where the scene has mirrors or glass (sharp GGX then holds "
                        "VPLs)");
  app.add_option_function<int>(
         "--caustic-photons", [&o](int n) { o.settings.caustic_photons = n, o.settings.caustics = o.caustics_given = true; },
         "ir/igi: photon paths shot per frame, >= 1; implies --caustics" +
             shown_default(kDefaults.settings.caustic_photons))
      ->check(integer<int>())->type_name("N");
  app.add_option_function<float>(
         "--caustic-radius", [&o](float r) { o.settings.caustic_radius = r, o.settings.caustics = o.caustics_given = true; },
         "ir/igi: photon gather radius, a fraction of the scene diagonal; implies --caustics" +
             shown_default(kDefaults.settings.caustic_radius))
      ->check(cli::number())->type_name("R");
}

void add_lightcuts_and_importance_options(CLI::App& app, RenderSettings& s) {
  app.add_option("--lightcuts-error", s.lightcuts_error, "lightcuts (over all --vpl-sets x --vpl-paths VPLs): refine "
                 "until every cluster's error bound is below E x the pixel's total, 0 < E < 1" + shown_default(kDefaults.settings.lightcuts_error))
      ->check(cli::number())->type_name("E");
  app.add_option("--lightcuts-max-cut", s.lightcuts_max_cut, "lightcuts: at most N nodes (shadow rays) in a cut" + shown_default(kDefaults.settings.lightcuts_max_cut))
      ->check(integer<int>())->type_name("N");
  app.add_option("--lightcuts-spacing", s.lightcuts_spacing,
                 "lightcuts: reconstruction cuts, full cuts every S pixels only, 0 = off" + shown_default(kDefaults.settings.lightcuts_spacing))
      ->check(integer<int>())->type_name("S");
  app.add_option("--lightcuts-block", s.lightcuts_block,
                 "lightcuts: one cut shared by the B x B pixels of a block on one diffuse surface, 0..8, 0 or 1 = a cut "
                 "per pixel; plain cuts only" + shown_default(kDefaults.settings.lightcuts_block))
      ->check(integer<int>())->type_name("B");
  app.add_option("--lightcuts-samples", s.lightcuts_samples,
                 "lightcuts: K = 1, 4, 9 ... 64 gather points per pixel (multidimensional)" + shown_default(kDefaults.settings.lightcuts_samples))
      ->check(integer<int>())->type_name("K");
  app.add_option("--importance", s.importance_paths, "ir/igi: start VPL light paths at lights by their estimated "
                 "share of the image, from N camera paths (light importance for the view), 0 = by power" + shown_default(kDefaults.settings.importance_paths))
      ->check(integer<int>())->type_name("N");
  app.add_option("--importance-floor", s.importance_floor, "ir/igi: share of light paths still started by power, "
                 "0..1" + shown_default(kDefaults.settings.importance_floor))->check(cli::number())->type_name("F");
  app.add_option_function<std::string>(
         "--bidir", [&s](const std::string& k) { s.bidir_vpls = k == "auto" ? kBidirAuto : std::stoi(k); },
         "ir/igi: bidirectional instant radiosity: per set, keep K of the VPLs of --vpl-paths light paths and R "
         "camera paths, by their estimated contribution; 0 = off; auto = where the view sees few of the light "
         "paths' VPLs, 2 x --vpl-paths light and camera paths and K = 2 x --vpl-paths, else off" +
             shown_default(bidir_text(kDefaults.settings.bidir_vpls)))
      ->check(CLI::Validator(
          [](std::string& k) -> std::string {
            return k == "auto" || integer<int>()(k).empty() ? "" : "expected an integer or auto, got '" + k + "'";
          },
          ""))
      ->type_name("K|auto");
  app.add_option("--bidir-camera-paths", s.bidir_camera_paths,
                 "ir/igi with --bidir: camera paths per set, 0 = --vpl-paths" + shown_default(kDefaults.settings.bidir_camera_paths))
      ->check(integer<int>())->type_name("R");
}

}  // namespace

void add_render_options(CLI::App& app, RenderOptions& o) {
  add_image_options(app, o);
  add_vpl_options(app, o.settings);
  add_filter_and_caustic_options(app, o);
  add_lightcuts_and_importance_options(app, o.settings);
}

SceneOptions scene_options(const RenderOptions& o) {
  SceneOptions options;
  options.light_units = o.light_units;
  options.camera_given = !o.camera_file.empty();
  if (!o.environment) return options;
  options.sky = *o.environment;
  options.sky->radiance *= o.environment_scale;
  options.sky->rotation = o.environment_rotation;
  return options;
}

void check_render_options(const CLI::App& app, const RenderOptions& o) {
  if (!o.environment && (app.count("--environment-scale") || app.count("--environment-rotation")))
    throw OptionError("--environment-scale and --environment-rotation need --environment");
  if (o.environment && o.environment->map.empty() && app.count("--environment-rotation"))
    throw OptionError("--environment-rotation turns a map: a constant sky (--environment R,G,B) has none");
  if (app.count("--exposure") && app.count("--ev"))
    throw OptionError("--exposure and --ev set the same exposure (--ev S is --exposure 2^S): give one");
  if (app.count("--max-depth"))
    throw OptionError("--max-depth was split: --path-depth (pt), --light-depth (VPL light paths) and "
                      "--specular-depth (mirrors and glass from the camera)");
  if (auto error = settings_error(o.settings)) throw OptionError(*error);
  // Before any work: an image that could not be written after the render.
  if (o.export_gltf.empty())
    if (auto error = image_path_error(o.output)) throw OptionError("-o " + *error);
  check_memory(o);
}

std::optional<std::string> choose_caustics(RenderOptions& o, const Scene& scene) {
  const bool vpl = o.settings.method == MethodKind::InstantRadiosity || o.settings.method == MethodKind::Igi;
  if (o.caustics_given || !vpl || o.settings.caustics ||
      !photons::has_specular_surfaces(scene, o.settings.glossy_threshold))
    return std::nullopt;
  o.settings.caustics = true;
  check_memory(o);
  return "caustics on: the scene has mirrors, glass or sharp glossy surfaces (" + std::to_string(o.settings.caustic_photons) +
         " photon paths a frame; --no-caustics leaves them out)";
}

static void declare(CLI::App& app, RenderOptions& o) {
  cli::take_last_by_default(app);
  cli::add_version_flag(app);
  add_render_options(app, o);
}

std::string render_usage(const std::string& program) {
  return cli::help<RenderOptions>("igi-render: renders one image of a scene with one method, in this process",
                                  program, declare);
}

RenderOptions parse_render_options(const std::vector<std::string>& args) {
  RenderOptions o;
  CLI::App app;
  declare(app, o);
  o.help = !cli::parse(app, args);
  if (!o.help) check_render_options(app, o);
  return o;
}

}  // namespace igi
