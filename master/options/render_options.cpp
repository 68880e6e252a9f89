#include "options/render_options.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <thread>

#include "cli/option_checks.h"
#include "core/settings_table.h"
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

std::string auto_text(int k) { return k == kBidirAuto ? "auto" : std::to_string(k); }

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
  app.add_option("--max-depth")->group("");  // split: refused with a message that says how
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

// An option its row says turns on a switch too (--caustic-photons: caustics);
// any caustics option means the scene does not choose (choose_caustics()).
void given(RenderOptions& o, const Setting& row) {
  if (const Setting* implied = *row.implies ? setting_of_field(row.implies) : nullptr)
    o.settings.*std::get<bool RenderSettings::*>(implied->member) = true;
  if (std::string(row.field) == "caustics" || std::string(row.implies) == "caustics") o.caustics_given = true;
}

// "ir/igi: what it does [default]": the methods that read it, and RenderSettings' default.
std::string setting_help(const Setting& row, const char* text, const std::string& shown) {
  const std::string methods = methods_text(row.methods);
  return (methods.empty() ? "" : methods + ": ") + text + shown;
}

void add_setting(CLI::App& app, RenderOptions& o, const Setting& row, MethodKind RenderSettings::*member) {
  app.add_option_function<std::string>(
         row.option, [&o, member](const std::string& m) { o.settings.*member = *parse_method(m); },
         setting_help(row, row.help, shown_default(std::string(method_name(kDefaults.settings.*member)))))
      ->check(cli::one_of({"pt", "ir", "igi", "lightcuts"}))->type_name(row.value);
}

void add_setting(CLI::App& app, RenderOptions& o, const Setting& row, bool RenderSettings::*member) {
  if (*row.option)
    app.add_flag_callback(row.option, [&o, &row, member] { o.settings.*member = true, given(o, row); },
                          setting_help(row, row.help, ""));
  if (*row.off_option)
    app.add_flag_callback(row.off_option, [&o, &row, member] { o.settings.*member = false, given(o, row); },
                          setting_help(row, row.off_help, ""));
}

void add_setting(CLI::App& app, RenderOptions& o, const Setting& row, int RenderSettings::*member) {
  if (row.bound == Bound::ClosedOrAuto) {  // --bidir K|auto
    app.add_option_function<std::string>(
           row.option, [&o, member](const std::string& k) { o.settings.*member = k == "auto" ? kBidirAuto : std::stoi(k); },
           setting_help(row, row.help, shown_default(auto_text(kDefaults.settings.*member))))
        ->check(CLI::Validator(
            [](std::string& k) -> std::string {
              return k == "auto" || integer<int>()(k).empty() ? "" : "expected an integer or auto, got '" + k + "'";
            },
            ""))
        ->type_name(row.value);
    return;
  }
  app.add_option_function<int>(
         row.option, [&o, &row, member](int v) { o.settings.*member = v, given(o, row); },
         setting_help(row, row.help, shown_default(kDefaults.settings.*member)))
      ->check(integer<int>())->type_name(row.value);
}

void add_setting(CLI::App& app, RenderOptions& o, const Setting& row, float RenderSettings::*member) {
  app.add_option_function<float>(
         row.option, [&o, &row, member](float v) { o.settings.*member = v, given(o, row); },
         setting_help(row, row.help, shown_default(double(kDefaults.settings.*member))))
      ->check(cli::number())->type_name(row.value);
}

// Every setting's option, as its row says (core/settings_table.h).
void add_settings_options(CLI::App& app, RenderOptions& o) {
  for (const Setting& row : settings_table())
    std::visit([&](auto member) { add_setting(app, o, row, member); }, row.member);
}

}  // namespace

void add_render_options(CLI::App& app, RenderOptions& o) {
  add_image_options(app, o);
  add_settings_options(app, o);
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
