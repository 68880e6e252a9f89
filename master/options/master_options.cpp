#include "options/master_options.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <climits>
#include <sstream>

#include "cli/option_checks.h"
#include "display/window_keys.h"
#include "options/liveness_options.h"
#include "protocol/curve.h"
#include "protocol/messages.h"

namespace igi {
namespace {

using cli::integer;
using cli::OptionError;

constexpr int kMaxLocalWorkers = 1024;
constexpr int kMaxFrames = 100000000;     // --frames and --first-frame: their sum stays an int
constexpr int kMaxWaitSeconds = 86400;    // --min-workers-wait

// The window's keys (display/window_keys.h), and what accumulates.
std::string window_help() {
  return "window keys:\n" + window_keys_text("  ") +
         "while the camera and settings are still, frames accumulate (new seed and sub-pixel position each)";
}

void add_network_options(CLI::App& app, MasterOptions& o) {
  const std::string group = "Cluster options";
  app.add_option("--workers", o.workers, "local igi-worker processes to start (0: only remote ones) [2]")
      ->check(integer(0, kMaxLocalWorkers))->group(group)->type_name("N");
  app.add_option("--worker-threads", o.worker_threads, "threads per local worker, 0 = cores / workers [0]")
      ->check(integer(0, cli::kMaxThreads))->group(group)->type_name("T");
  app.add_option("--listen", o.listen, "where workers connect [tcp://127.0.0.1:0 = loopback, any free port]; name "
                 "another interface (tcp://0.0.0.0:5555) to open it to a network: that needs CURVE (--key and "
                 "--authorized-keys)")->type_name("ENDPOINT")->group(group);
  app.add_option_function<std::string>(
         "--key", [&o](const std::string& file) { o.key_file = file, o.curve = true; },
         "the master's secret key (igi-keys new NAME writes NAME.key): turns on CURVE authentication and "
         "encryption; workers get NAME.pub (--master-key)")->type_name("FILE")->group(group);
  app.add_option("--authorized-keys", o.authorized_keys, "workers allowed to connect: a folder of their .pub files, "
                 "or a file with one Z85 public key per line (local workers are always allowed)")
      ->type_name("PATH")->group(group);
  app.add_flag("--curve", o.curve, "CURVE on a loopback endpoint too (needs --key)")->group(group);
  app.add_option("--viewer-listen", o.viewer_listen, "leave the window to igi-view: no window here, one viewer at a "
                 "time drives the camera and settings through this endpoint (tcp://127.0.0.1:5600; from a laptop "
                 "through ssh -L), always with CURVE: needs --key and --viewer-keys")
      ->type_name("ENDPOINT")->group(group);
  app.add_option("--viewer-keys", o.viewer_keys, "viewers allowed to connect to --viewer-listen: a folder of their "
                 ".pub files (igi-keys new NAME), or a file with one Z85 public key per line")
      ->type_name("PATH")->group(group);
  app.add_option("--viewer-codec", o.viewer_codec, "the viewer's frames while the view moves: h264 (libx264, "
                 "low latency, within --viewer-mbit) or zstd (lossless 8-bit); a still view's frames are always "
                 "lossless [h264]")->check(cli::one_of({"h264", "zstd"}))->type_name("h264|zstd")->group(group);
  app.add_option("--viewer-mbit", o.viewer_mbit, "h264: the most Mbit/s the moving frames take; 0: no cap (x264's default quality) [20]")
      ->check(cli::bounded_number(10000.0))->check(cli::non_negative_number())->type_name("M")->group(group);
  app.add_option("--credits", o.credits, "jobs a worker holds at once [2]")
      ->check(integer<int>(1, protocol::kMaxCredits))->group(group)->type_name("K");
  add_liveness_options(app, o.heartbeat_ms, o.timeout_ms, group);
  app.add_option("--pixels", o.pixels, "pixels on the wire: float, half (6 bytes a pixel, display frames), rgb9e5 "
                 "(4 bytes: 9 bits a channel under a shared exponent, HDR; display frames over slow links, with "
                 "--pixel-codec zstd or lz4) or auto: float when -o is a float file (.exr, .hdr, .pfm, .tif), else half [auto]")
      ->check(cli::one_of({"auto", "float", "half", "rgb9e5"}))->group(group)->type_name("auto|float|half|rgb9e5");
  app.add_option("--pixel-codec", o.pixel_codec, "workers pack their tiles' pixels (and surfaces): raw, zstd or lz4 "
                 "(lossless; rendered rgb9e5 display frames take about 1 byte a pixel with zstd, 1.7 with lz4, which "
                 "the master unpacks in a third of zstd's time): for links slower than the pixels [raw]")
      ->check(cli::one_of({"raw", "zstd", "lz4"}))->group(group)->type_name("raw|zstd|lz4");
  app.add_option("--io-threads", o.io_threads, "ZeroMQ I/O threads [1]: more pay only past ~100,000 tiles a second")
      ->check(integer(1, cli::kMaxIoThreads))->group(group)->type_name("N");
}

void add_run_options(CLI::App& app, MasterOptions& o) {
  const std::string group = "Run options";
  app.add_option("--frames", o.frames, "headless: render F frames and write them (-o); default: a window")
      ->check(integer(0, kMaxFrames))->group(group)->type_name("F");
  app.add_option("--first-frame", o.first_frame, "headless: start at frame I (camera path, seed and file names) [0]")
      ->check(integer(0, kMaxFrames))->group(group)->type_name("I");
  app.add_option("--min-workers", o.min_workers, "headless: hold the first frame until N workers have joined, at "
                 "most --min-workers-wait seconds, then start with those present [0]")
      ->check(integer(0, INT_MAX))->group(group)->type_name("N");
  app.add_option("--min-workers-wait", o.min_workers_wait, "see --min-workers [30]")
      ->check(integer(0, kMaxWaitSeconds))->group(group)->type_name("S");
  app.add_flag("--progressive", o.progressive, "headless: accumulate frames, advancing the seed")->group(group);
  app.add_option("--time-step", o.render.time_step, "animated scenes: seconds of animation time a frame [0.0333]")
      ->check(cli::bounded_number(protocol::kMaxSceneTime))->group(group)->type_name("S");
  app.add_flag("--loop", o.render.loop, "animated scenes: wrap the time into the animation's length")->group(group);
  app.add_option_function<std::string>(
         "--camera-path", [&o](const std::string& v) {
           o.camera_path.kind = v == "orbit" ? CameraPath::Kind::Orbit : CameraPath::Kind::Swing;
         },
         "headless: orbit turns the camera about a pivot on its line of sight near the scene's centre, one full "
         "turn over the frames (a scene seen from outside); swing turns it --swing degrees to either side and back "
         "(a scene seen through an opening, as the Cornell box)")
      ->check(cli::one_of({"orbit", "swing"}))->group(group)->type_name("orbit|swing");
  app.add_option("--orbit-step", o.camera_path.orbit_step_degrees,
                 "orbit: degrees a frame (negative: the other way), 0 = one full turn over --first-frame + --frames [0]")
      ->check(cli::bounded_number(360.0))->group(group)->type_name("DEG");
  app.add_option("--swing", o.camera_path.swing_degrees, "swing: the widest turn to either side, in degrees [" +
                 std::to_string(int(CameraPath{}.swing_degrees)) + "]")
      ->check(cli::bounded_number(180.0))->group(group)->type_name("DEG");
  app.add_option("--stats", o.stats, "per-frame statistics, JSON Lines: a line per frame, and the run's totals")
      ->type_name("FILE.jsonl")->group(group);
  app.add_flag("--no-write", o.no_write, "headless: write no images (benchmarks)")->group(group);
  app.add_option("--screenshot-after", o.screenshot_after, "window: save --screenshot after N accumulated frames [4], "
                 "then exit")->check(integer(1, INT_MAX))->group(group)->type_name("N");
  app.add_option_function<std::string>(
         "--panel", [&o](const std::string& v) { o.panel = v == "on"; },
         "window: the settings panel and the frame rate in a column beside the image at start (Tab toggles them) [on]")
      ->check(cli::one_of({"on", "off"}))->group(group)->type_name("on|off");
  app.add_option("--frame-budget-ms", o.frame_budget_ms,
                 "window: while the camera or settings change, render previews (fewer pixels, cheaper settings) "
                 "that take about this long; 0 = full frames only [" + std::to_string(int(kWindowFrameBudgetMs)) + "]")
      ->check(cli::non_negative_number())->check(cli::bounded_number(10000.0))->group(group)->type_name("MS");
  app.add_option_function<std::string>(
         "--previews", [&o](const std::string& v) { o.sharp_previews = v == "sharp"; },
         "window: previews while the view changes: sharp (camera rays, textures and edges at every pixel, light on "
         "a coarser lattice upsampled along the surfaces; after a stop, frames refine up to the full frame) or "
         "coarse (fewer pixels, the full frame at once after a stop) [sharp]")
      ->check(cli::one_of({"sharp", "coarse"}))->group(group)->type_name("sharp|coarse");
  app.add_option_function<std::string>(
         "--reproject", [&o](const std::string& v) { o.reproject = v == "on"; },
         "window: carry the accumulated image through camera moves where the surface is the same [on]")
      ->check(cli::one_of({"on", "off"}))->group(group)->type_name("on|off");
  app.add_option("--history-frames", o.history_frames,
                 "window: frames of history a carried pixel keeps at most [16]")
      ->check(integer(1, 1 << 20))->group(group)->type_name("K");
  app.add_option("--motion", o.motion, "headless: a scripted user moves the camera (drag turns it 30 degrees a second aside and "
                 "back, walk holds W) for --motion-seconds, then holds still for --still-seconds; frames shown are logged "
                 "in --motion-out (the motion benchmark)")
      ->check(cli::one_of({"drag", "walk"}))->group(group)->type_name("drag|walk");
  app.add_option("--motion-out", o.motion_out, "--motion: the folder for its log, images and cameras [motion]")
      ->group(group)->type_name("DIR");
  app.add_option("--motion-seconds", o.motion_seconds, "--motion: seconds of motion [2]")
      ->check(cli::non_negative_number())->check(cli::bounded_number(600.0))->group(group)->type_name("S");
  app.add_option("--still-seconds", o.still_seconds, "--motion: seconds still after it [4]")
      ->check(cli::non_negative_number())->check(cli::bounded_number(600.0))->group(group)->type_name("S");
  app.add_flag("--motion-legacy", o.motion_legacy,
               "--motion: as before motion was handled (no budget, stale frames dropped, history thrown away)")
      ->group(group);
  app.add_option("--overlay", o.overlay, "window: tint tiles by the worker that rendered them: off, tint, solid [off]")
      ->check(cli::one_of({"off", "tint", "solid"}))->group(group)->type_name("off|tint|solid");
}

// Test hooks: not in --help.
void add_test_options(CLI::App& app, MasterOptions& o, std::string& panel_edit) {
  app.add_option("--test-kill-worker-after", o.kill_worker_after)->check(integer(0, INT_MAX))->group("");
  app.add_option("--test-force-duplicates", o.force_duplicates)->check(integer(0, INT_MAX))->group("");
  app.add_option("--test-stop-worker-after", o.stop_worker_after)->check(integer(0, INT_MAX))->group("");
  app.add_option("--test-send-hwm", o.send_hwm)->check(integer(0, INT_MAX))->group("");
  app.add_option("--test-panel-edit", panel_edit)->group("");
  app.add_flag("--test-show-help", o.help)->group("");
}

void declare(CLI::App& app, MasterOptions& o, std::string& panel_edit) {
  cli::take_last_by_default(app);
  cli::add_version_flag(app);
  app.footer(window_help());
  add_network_options(app, o);
  add_run_options(app, o);
  add_test_options(app, o, panel_edit);
  add_render_options(app, o.render);
}

// The command line without the panel edit, then the edit's words (e.g. "--vpl-paths 2 --clamp 0"): the last counts.
RenderSettings edited_settings(const std::vector<std::string>& args, const std::string& edit) {
  std::vector<std::string> edited;
  for (size_t i = 0; i < args.size(); ++i)
    if (args[i] == "--test-panel-edit") ++i;
    else edited.push_back(args[i]);
  std::istringstream words(edit);
  for (std::string word; words >> word;) edited.push_back(word);
  return parse_master_options(edited).render.settings;
}

// A viewer drives the session and sees its image: always CURVE, even on
// loopback, which every user of a shared login node can reach.
void check_viewer_security(const MasterOptions& o) {
  if (o.viewer_listen.empty()) {
    if (!o.viewer_keys.empty()) throw OptionError("--viewer-keys: needs --viewer-listen ENDPOINT");
    return;
  }
  if (o.frames > 0 || !o.motion.empty())
    throw OptionError("--viewer-listen: a viewer takes the window's place; not with --frames or --motion");
  if (o.key_file.empty() || o.viewer_keys.empty())
    throw OptionError("--viewer-listen needs CURVE: --key MASTER.key (the viewer gets MASTER.pub) and --viewer-keys "
                      "PATH (the viewers' .pub files; make keys with igi-keys new NAME)");
}

// Refuses what would expose workers' jobs and pixels, before anything is bound.
void check_security(const MasterOptions& o) {
  if (!protocol::is_local_endpoint(o.listen) && !o.curve)
    throw OptionError("--listen " + o.listen +
                      " can be reached from other machines, so CURVE authentication and encryption are "
                      "required: give --key MASTER.key and --authorized-keys DIR (make keys with "
                      "igi-keys new NAME), or listen on tcp://127.0.0.1");
  if (o.curve && o.key_file.empty())
    throw OptionError("CURVE needs the master's secret key: --key MASTER.key (igi-keys new MASTER)");
  if (o.curve && o.authorized_keys.empty() && (o.workers == 0 || !protocol::is_local_endpoint(o.listen)))
    throw OptionError("CURVE needs the workers' public keys: --authorized-keys DIR (their .pub files)");
  if (!o.authorized_keys.empty() && !o.curve)
    throw OptionError("--authorized-keys needs --key MASTER.key: without CURVE every peer is let in");
  check_viewer_security(o);
}

}  // namespace

void declare_master_options(CLI::App& app, MasterOptions& o) {
  static std::string panel_edit;  // a hidden test hook: the reference lists no hidden option
  declare(app, o, panel_edit);
}

std::string master_usage(const std::string& program) {
  std::string panel_edit;
  return cli::help<MasterOptions>("igi-master: renders frames on igi-worker processes (local and remote) and writes "
                                  "them (--frames F) or shows them in a window", program,
                                  [&](CLI::App& app, MasterOptions& o) { declare(app, o, panel_edit); });
}

PixelFormat session_pixel_format(const MasterOptions& o) {
  if (o.pixels == "float") return PixelFormat::Float32;
  if (o.pixels == "half") return PixelFormat::Float16;
  if (o.pixels == "rgb9e5") return PixelFormat::Rgb9e5;
  if (o.frames == 0) return PixelFormat::Float16;  // the window
  std::string ext = o.render.output.substr(o.render.output.find_last_of('.') + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  const bool float_file = ext == "exr" || ext == "hdr" || ext == "pfm" || ext == "tif" || ext == "tiff";
  return float_file ? PixelFormat::Float32 : PixelFormat::Float16;
}

SessionSettings session_settings(const MasterOptions& o) {
  SessionSettings s;
  s.listen = o.listen;
  s.settings = o.render.settings;
  s.tile_size = o.render.tile_size;
  s.pixel_format = session_pixel_format(o);
  s.pixel_codec = o.pixel_codec;
  s.credits = o.credits;
  s.heartbeat_ms = o.heartbeat_ms;
  s.timeout_ms = o.timeout_ms;
  s.detailed_stats = !o.stats.empty();
  s.quiet = o.render.quiet;
  s.send_hwm = o.send_hwm;
  s.force_duplicates = o.force_duplicates;
  return s;
}

// igi-render's options that igi-master would otherwise take and ignore.
static void check_render_only_options(const CLI::App& app, const MasterOptions& o) {
  if (app.count("--spp") && o.render.settings.method != MethodKind::PathTracer)
    throw OptionError("--spp: igi-master renders one pass of " + std::string(method_name(o.render.settings.method)) +
                      " a frame (--spp is pt's samples per pixel here); --progressive accumulates the frames, or use "
                      "igi-render --spp N");
  if (app.count("--threads"))
    throw OptionError("--threads: igi-master renders nothing itself; --worker-threads T sets its local workers' "
                      "threads (igi-worker --threads for the others)");
  if (app.count("--export-gltf"))
    throw OptionError("--export-gltf: igi-render writes the scene (igi-render --scene S --export-gltf FILE)");
  if (app.count("--show"))
    throw OptionError("--show: igi-master opens a window whenever --frames is not given");
}

// The camera path's options without a path, or a path without frames to follow it.
static void check_camera_path(const CLI::App& app, MasterOptions& o) {
  const CameraPath::Kind kind = o.camera_path.kind;
  if (app.count("--orbit-step") && kind != CameraPath::Kind::Orbit)
    throw OptionError("--orbit-step: needs --camera-path orbit");
  if (app.count("--swing") && kind != CameraPath::Kind::Swing) throw OptionError("--swing: needs --camera-path swing");
  if (kind != CameraPath::Kind::None && o.frames == 0)
    throw OptionError("--camera-path: headless only (--frames F); in the window the camera is yours to move");
  o.camera_path.frames = o.first_frame + o.frames;
}

MasterOptions parse_master_options(const std::vector<std::string>& args) {
  MasterOptions o;
  std::string panel_edit;
  CLI::App app;
  declare(app, o, panel_edit);
  o.render.help = !cli::parse(app, args);
  if (o.render.help) return o;
  check_render_options(app, o.render);
  check_render_only_options(app, o);
  check_camera_path(app, o);
  if (!panel_edit.empty()) o.test_panel_settings = edited_settings(args, panel_edit);
  check_security(o);
  check_liveness(o.heartbeat_ms, o.timeout_ms);
  return o;
}

}  // namespace igi
